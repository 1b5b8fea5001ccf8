// encore batch on generated scenes (no shared models needed) and a malformed file: every model's
// images and transforms.json, the bad file in failures.jsonl with render's message, exit 1;
// reruns skip finished models; a batch killed with SIGKILL or stopped with SIGINT resumes with
// nothing half-written.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "BatchCommandSupport.h"
#include "CommandRunner.h"
#include "TestFiles.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"
#include "image/ImageCompare.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

// Every finished model: `views` decodable RGBA images with a transparent corner and some opaque
// coverage, a transforms.json naming them and a metadata.json with no blank view.
void expectFinishedModel(const fs::path& folder, int views) {
    const nlohmann::json transforms =
        nlohmann::json::parse(readBytes(folder / "transforms.json"), nullptr, false);
    ASSERT_FALSE(transforms.is_discarded()) << folder;
    const nlohmann::json metadata =
        nlohmann::json::parse(readBytes(folder / "metadata.json"), nullptr, false);
    ASSERT_FALSE(metadata.is_discarded()) << folder;
    EXPECT_EQ(metadata["views"], views);
    EXPECT_EQ(metadata["blankViews"], nlohmann::json::array()) << folder;
    EXPECT_EQ(metadata["sha256"].get<std::string>().size(), 64u);
    EXPECT_GT(transforms["camera_angle_x"].get<double>(), 0.0);
    ASSERT_EQ(transforms["frames"].size(), std::size_t(views));
    for (int view = 0; view < views; ++view) {
        const std::string stem = transforms["frames"][view]["file_path"].get<std::string>();
        EXPECT_EQ(transforms["frames"][view]["transform_matrix"].size(), 4u);
        auto image = image::readImage(folder / (stem.substr(2) + ".png"));
        ASSERT_TRUE(image.ok()) << folder << " " << stem;
        EXPECT_EQ(image->pixel(0, 0)[3], 0) << "the background is transparent";
        bool opaque = false;
        for (std::size_t i = 3; i < image->pixels.size(); i += 4) {
            opaque = opaque || image->pixels[i] == 255;
        }
        EXPECT_TRUE(opaque) << folder << " " << stem << " shows nothing";
    }
}

// A command prefix that runs the batch in the background and sends it `signal` as soon as its
// first model is finished (a transforms.json exists under `output`): the moment when the next
// models' images are being drawn, encoded and written.
std::string signalAfterFirstModel(const fs::path& dir,
                                  const fs::path& output,
                                  const std::string& signal) {
    const fs::path script = dir / ("signal-" + signal + ".sh");
    std::ofstream(script) << "out=\"$1\"; shift\n"
                             "\"$@\" & pid=$!\n"
                             "while kill -0 $pid 2>/dev/null && [ -z \"$(find \"$out\" -name "
                             "transforms.json 2>/dev/null | head -n 1)\" ]; do sleep 0.01; done\n"
                             "kill -s "
                          << signal
                          << " $pid 2>/dev/null\n"
                             "wait $pid\n";
    return "sh " + quote(script.string()) + " " + quote(output.string());
}

TEST(BatchCommandTest, RendersEveryGoodModelAndListsTheBadOne) {
    const fs::path input = makeCollection("batch-cli-input", 3, 6);
    const fs::path output = makeTempDir("batch-cli-output");
    const CommandResult run =
        runEncore(batchArguments(input, output, "--views 4 --size 96x64 --quiet"));
    EXPECT_EQ(run.exitCode, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("Vulkan"), std::string::npos)
        << "GPU tests need Dawn's Vulkan backend: " << run.err;
    EXPECT_NE(run.out.find("3 rendered, 1 failed, 0 skipped of 4 models"), std::string::npos)
        << run.out;
    for (const char* name : {"set0/model", "set1/model", "more/scene2"}) {
        expectFinishedModel(output / name, 4);
        auto image = image::readImage(output / name / "000.png");
        ASSERT_TRUE(image.ok());
        EXPECT_EQ(image->width, 96u);
        EXPECT_EQ(image->height, 64u);
    }
    // The two model.glb differ (different seeds): their outputs are their own.
    EXPECT_NE(readBytes(output / "set0/model/000.png"), readBytes(output / "set1/model/000.png"));

    const auto failures = jsonLines(output / "failures.jsonl");
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(fs::path(failures[0]["file"].get<std::string>()), input / "broken.gltf");
    EXPECT_EQ(failures[0]["stage"], "load");
    const CommandResult render = runEncore("render " + quote((input / "broken.gltf").string()) +
                                           " -o " + quote((output / "x.png").string()));
    EXPECT_EQ(render.err, "error: " + failures[0]["error"].get<std::string>() + "\n");
    EXPECT_TRUE(filesUnder(output, ".part").empty());
    // No WebGPU error was reported on the way.
    EXPECT_EQ(run.err.find("error: WebGPU"), std::string::npos) << run.err;

    // Again: everything finished is skipped, the bad file is tried (and listed) again.
    const auto firstWrite = fs::last_write_time(output / "set0/model/000.png");
    const CommandResult rerun =
        runEncore(batchArguments(input, output, "--views 4 --size 96x64 --quiet"));
    EXPECT_EQ(rerun.exitCode, 1);
    EXPECT_NE(rerun.out.find("0 rendered, 1 failed, 3 skipped of 4 models"), std::string::npos)
        << rerun.out;
    EXPECT_EQ(fs::last_write_time(output / "set0/model/000.png"), firstWrite);
    EXPECT_EQ(jsonLines(output / "failures.jsonl").size(), 1u);
}

TEST(BatchCommandTest, RandomViewsFromASeedAndAJsonList) {
    const fs::path input = makeCollection("batch-cli-random", 1, 3);
    fs::remove(input / "broken.gltf");
    std::ofstream(input / "list.json") << "[\"set0/model.glb\"]";
    const fs::path output = makeTempDir("batch-cli-random-output");
    const CommandResult run = runEncore(batchArguments(
        input / "list.json", output / "a", "--random-views 3 --seed 5 --size 32 --quiet"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    expectFinishedModel(output / "a" / "model", 3);
    const CommandResult again = runEncore(batchArguments(
        input / "list.json", output / "b", "--random-views 3 --seed 5 --size 32 --quiet"));
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(readBytes(output / "a/model/transforms.json"),
              readBytes(output / "b/model/transforms.json"));
    EXPECT_EQ(readBytes(output / "a/model/002.png"), readBytes(output / "b/model/002.png"));
}

// --normals and --depth: a normal and a 16-bit depth image beside every view: unit vectors
// where the model is opaque, depths within the unit box around the orbit's centre.
TEST(BatchCommandTest, NormalAndDepthImagesBesideTheViews) {
    const fs::path input = makeCollection("batch-cli-normals", 1, 6);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-cli-normals-output");
    const CommandResult run =
        runEncore(batchArguments(input, output, "--views 2 --size 64 --normals --depth --quiet"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    const fs::path model = output / "set0" / "model";
    expectFinishedModel(model, 2);
    const nlohmann::json transforms = nlohmann::json::parse(readBytes(model / "transforms.json"));
    EXPECT_EQ(transforms["frames"][1]["normal_file_path"], "./001_normal");
    auto normals = image::readImage(model / "001_normal.png");
    ASSERT_TRUE(normals.ok());
    EXPECT_EQ(normals->pixel(0, 0)[3], 0);
    std::vector<double> lengths;
    for (std::size_t i = 0; i < normals->pixels.size(); i += 4) {
        if (normals->pixels[i + 3] == 255) {
            double squared = 0.0;
            for (std::size_t c = 0; c < 3; ++c) {
                const double component = normals->pixels[i + c] / 255.0 * 2.0 - 1.0;
                squared += component * component;
            }
            lengths.push_back(std::sqrt(squared));
        }
    }
    ASSERT_FALSE(lengths.empty());
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    EXPECT_NEAR(lengths[lengths.size() / 2], 1.0, 0.02);

    EXPECT_EQ(transforms["frames"][1]["depth_file_path"], "./001_depth");
    const double scale = transforms["depth_scale"].get<double>();
    EXPECT_NEAR(scale, 3.0 / 65535.0, 1e-9);                 // Twice the default distance of 1.5.
    auto depth = image::readImage(model / "001_depth.png");  // 16 bits read as their high byte.
    auto color = image::readImage(model / "001.png");
    ASSERT_TRUE(depth.ok() && color.ok());
    std::size_t covered = 0;
    for (std::uint32_t y = 0; y < depth->height; ++y) {
        for (std::uint32_t x = 0; x < depth->width; ++x) {
            const double z = depth->pixel(x, y)[0] * 256.0 * scale;
            if (color->pixel(x, y)[3] == 0) {
                EXPECT_EQ(depth->pixel(x, y)[0], 0) << x << "," << y << " is empty";
            } else if (color->pixel(x, y)[3] == 255) {
                ++covered;
                // Within the unit box's half-diagonal of the centre, 1.5 away.
                EXPECT_GT(z, 1.5 - 0.87 - 0.02) << x << "," << y;
                EXPECT_LT(z, 1.5 + 0.87) << x << "," << y;
            }
        }
    }
    EXPECT_GT(covered, 0u);
    // Run again with the same images: finished.
    EXPECT_NE(
        runEncore(batchArguments(input, output, "--views 2 --size 64 --normals --depth --quiet"))
            .out.find("1 skipped"),
        std::string::npos);
}

// --top-light adds a light from above: the same views come out brighter.
TEST(BatchCommandTest, TopLightBrightensTheViews) {
    const fs::path input = makeCollection("batch-cli-top-light", 1, 6);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-cli-top-light-output");
    ASSERT_EQ(
        runEncore(batchArguments(input, output / "plain", "--views 1 --size 64 --quiet")).exitCode,
        0);
    const CommandResult lit = runEncore(
        batchArguments(input, output / "lit", "--views 1 --size 64 --top-light 5 --quiet"));
    ASSERT_EQ(lit.exitCode, 0) << lit.out << lit.err;
    auto brightness = [](const fs::path& png) {
        auto image = image::readImage(png);
        EXPECT_TRUE(image.ok());
        double sum = 0.0;
        for (std::size_t i = 0; i < image->pixels.size(); i += 4) {
            sum += image->pixels[i] + image->pixels[i + 1] + image->pixels[i + 2];
        }
        return sum;
    };
    EXPECT_GT(brightness(output / "lit/set0/model/000.png"),
              1.05 * brightness(output / "plain/set0/model/000.png"));
}

// --png-compression fast writes the same pixels (views, normals, 16-bit depth) in other bytes;
// an unknown value is a usage error.
TEST(BatchCommandTest, FastPngCompressionKeepsThePixels) {
    const fs::path input = makeCollection("batch-cli-png", 1, 6);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-cli-png-output");
    const std::string common = "--views 2 --size 96 --normals --depth --quiet";
    ASSERT_EQ(runEncore(batchArguments(input, output / "small", common)).exitCode, 0);
    const CommandResult fast =
        runEncore(batchArguments(input, output / "fast", common + " --png-compression fast"));
    ASSERT_EQ(fast.exitCode, 0) << fast.out << fast.err;
    for (const char* file : {"000.png", "001.png", "001_normal.png", "001_depth.png"}) {
        const fs::path small = output / "small/set0/model" / file;
        const fs::path quick = output / "fast/set0/model" / file;
        EXPECT_NE(readBytes(small), readBytes(quick))
            << file << ": the same bytes, so no other encoder";
        auto a = image::readImage(small);
        auto b = image::readImage(quick);
        ASSERT_TRUE(a.ok() && b.ok()) << file;
        EXPECT_TRUE(a->pixels == b->pixels) << file;
    }
    const CommandResult bad =
        runEncore(batchArguments(input, output / "bad", common + " --png-compression tiny"));
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("--png-compression"), std::string::npos) << bad.err;
}

// --lod-error draws coarser levels where the views can hardly tell (at half a pixel every view
// within SSIM 0.98 of full detail, yet not the same pixels) through gpu-culling-bundles, which it
// selects; with a strategy that does not cull on the GPU it is refused before anything renders.
TEST(BatchCommandTest, LevelsOfDetailKeepTheLookAndNeedAGpuCullingStrategy) {
    const fs::path input = makeTempDir("batch-cli-lod");
    const CommandResult gen = runEncore("gen --objects 60 --meshes 3 --tessellation 48 -o " +
                                        quote((input / "fine.glb").string()));
    ASSERT_EQ(gen.exitCode, 0) << gen.err;
    const fs::path output = makeTempDir("batch-cli-lod-output");
    const std::string common = "--views 3 --size 256 --quiet";
    ASSERT_EQ(runEncore(batchArguments(input, output / "full",
                                       common + " --strategy gpu-culling-bundles"))
                  .exitCode,
              0);
    const CommandResult lod =
        runEncore(batchArguments(input, output / "lod", common + " --lod-error 0.5"));
    ASSERT_EQ(lod.exitCode, 0) << lod.out << lod.err;
    bool anyDifferent = false;
    for (const char* file : {"000.png", "001.png", "002.png"}) {
        auto full = image::readImage(output / "full/fine" / file);
        auto coarse = image::readImage(output / "lod/fine" / file);
        ASSERT_TRUE(full.ok() && coarse.ok()) << file;
        auto ssim = image::ssimLuminance(*full, *coarse);
        ASSERT_TRUE(ssim.ok()) << ssim.error().message;
        EXPECT_GE(*ssim, 0.98) << file;
        anyDifferent = anyDifferent || full->pixels != coarse->pixels;
    }
    EXPECT_TRUE(anyDifferent) << "no view changed: were coarser levels drawn at all?";

    const CommandResult refused = runEncore(
        batchArguments(input, output / "refused", common + " --lod-error 1 --strategy bundles"));
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_NE(refused.err.find("gpu-culling or the visibility strategy"), std::string::npos)
        << refused.err;
    EXPECT_FALSE(fs::exists(output / "refused/fine/000.png"));
}

// A batch of `count` generated models (no bad file) sent `signal` after its first model.
struct SignalledRun {
    fs::path input;
    fs::path output;
    std::string arguments;
    CommandResult result;
};

SignalledRun signalledRun(const std::string& name,
                          int count,
                          const std::string& signal,
                          const std::string& extra = "") {
    SignalledRun run;
    run.input = makeCollection(name, count, 40);
    fs::remove(run.input / "broken.gltf");
    run.output = makeTempDir(name + "-output");
    run.arguments =
        batchArguments(run.input, run.output, "--views 16 --size 128 --jobs 2 --quiet " + extra);
    run.result =
        runEncoreThrough(signalAfterFirstModel(run.input, run.output, signal), run.arguments);
    return run;
}

// Killed without warning at some moment of the run, then run again: the second run finishes
// every model, and no image is half-written at any point.
void expectKilledRunResumes(const SignalledRun& run) {
    EXPECT_EQ(run.result.exitCode, 137)
        << "not killed (128 + SIGKILL): " << run.result.out << run.result.err;
    const fs::path& input = run.input;
    const fs::path& output = run.output;
    const std::string& arguments = run.arguments;
    for (const fs::path& png : filesUnder(output, ".png")) {
        EXPECT_TRUE(image::readImage(png).ok()) << png << " is half-written";
    }
    const CommandResult rerun = runEncore(arguments);
    ASSERT_EQ(rerun.exitCode, 0) << rerun.out << rerun.err;
    EXPECT_NE(rerun.out.find("0 failed"), std::string::npos) << rerun.out;
    EXPECT_TRUE(filesUnder(output, ".part").empty());
    std::vector<fs::path> models;
    for (const fs::path& model : filesUnder(input, ".glb")) {
        models.push_back(output / model.lexically_relative(input).replace_extension());
    }
    ASSERT_EQ(models.size(), 8u);
    for (const fs::path& model : models) {
        expectFinishedModel(model, 16);
    }
}

TEST(BatchCommandTest, SigkillMidRunThenRerunCompletes) {
    expectKilledRunResumes(signalledRun("batch-cli-kill", 8, "KILL"));
}

// The same with two device threads (two devices on the one adapter) writing at once.
TEST(BatchCommandTest, SigkillMidRunOnTwoDevicesThenRerunCompletes) {
    expectKilledRunResumes(signalledRun("batch-cli-kill-devices", 8, "KILL", "--devices 0,0"));
}

// SIGTERM stops the batch as SIGINT does. Ten models, as there: on a loaded machine the signal
// may come late, and the batch must still have models left to refuse.
TEST(BatchCommandTest, SigtermStopsCleanly) {
    const SignalledRun run = signalledRun("batch-cli-term", 10, "TERM");
    EXPECT_EQ(run.result.exitCode, 130) << run.result.out << run.result.err;
    EXPECT_NE(run.result.out.find("interrupted"), std::string::npos) << run.result.out;
    EXPECT_TRUE(filesUnder(run.output, ".part").empty());
}

// Every device thread stops starting models; the models in flight on each are finished.
TEST(BatchCommandTest, SigtermStopsEveryDeviceCleanly) {
    const SignalledRun run = signalledRun("batch-cli-term-devices", 6, "TERM", "--devices 0,0");
    EXPECT_EQ(run.result.exitCode, 130) << run.result.out << run.result.err;
    EXPECT_NE(run.result.out.find("interrupted"), std::string::npos) << run.result.out;
    EXPECT_TRUE(filesUnder(run.output, ".part").empty());
    const CommandResult rerun = runEncore(run.arguments);
    ASSERT_EQ(rerun.exitCode, 0) << rerun.out << rerun.err;
    // The models finished before the signal are skipped, the rest rendered.
    EXPECT_NE(rerun.out.find(" rendered, 0 failed, "), std::string::npos) << rerun.out;
    EXPECT_EQ(rerun.out.find(" 0 skipped"), std::string::npos) << "nothing resumed: " << rerun.out;
    EXPECT_NE(rerun.out.find(" of 6 models"), std::string::npos) << rerun.out;
}

// SIGINT finishes the files in flight and exits with 130 and a summary.
TEST(BatchCommandTest, SigintStopsCleanly) {
    // Ten models: on a loaded machine the signal may come late, and the batch must still have
    // models left to refuse.
    constexpr int kModels = 10;
    const SignalledRun run = signalledRun("batch-cli-int", kModels, "INT");
    const CommandResult& stopped = run.result;
    const fs::path& output = run.output;
    const std::string& arguments = run.arguments;
    EXPECT_EQ(stopped.exitCode, 130) << stopped.out << stopped.err;
    EXPECT_NE(stopped.out.find("interrupted"), std::string::npos) << stopped.out;
    EXPECT_TRUE(filesUnder(output, ".part").empty());
    // Models whose views were in flight were finished; none was started afterwards.
    std::size_t finished = 0;
    for (const fs::path& json : filesUnder(output, ".json")) {
        finished += json.filename() == "transforms.json" ? 1 : 0;
    }
    EXPECT_GE(finished, 1u);
    EXPECT_LT(finished, std::size_t(kModels));
    EXPECT_EQ(filesUnder(output, ".png").size(), finished * 16);
    const CommandResult rerun = runEncore(arguments);
    ASSERT_EQ(rerun.exitCode, 0) << rerun.out << rerun.err;
    EXPECT_NE(rerun.out.find(std::to_string(kModels - finished) + " rendered, 0 failed, " +
                             std::to_string(finished) + " skipped"),
              std::string::npos)
        << rerun.out;
}

}  // namespace
}  // namespace encore::test
