// encore batch's defences against files that would stall or exhaust it (issue 29):
// --model-timeout abandons a model whose load runs past the limit while the others render,
// --max-texture-size downscales large images while loading, recording them in metadata.json, and
// a device lost mid-batch is created again, the models in flight drawn again.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "BatchCommandSupport.h"
#include "BatchOutput.h"
#include "CommandRunner.h"
#include "GltfBuilder.h"
#include "TestPaths.h"
#include "TextureFixtures.h"
#include "core/FileIO.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const fs::path& path) {
    return nlohmann::json::parse(readBytes(path), nullptr, false);
}

// A file whose load takes minutes: thousands of image entries, each the same 2048x2048 PNG
// decoded (and downscaled) again, 16 ms of CPU each on the 2-core VM (200 of them: 3.2 s of CPU,
// 10 s at load 10), so 5000 take about 80 s of CPU, eight times the limit of the test below.
// Its memory stays that of one image at a time.
void writeSlowModel(const fs::path& dir) {
    ASSERT_TRUE(
        writeFile(dir / "huge.png", encodePngBytes(solidImage({90, 140, 200, 255}, 2048, 2048)))
            .ok());
    GltfBuilder builder = texturedQuad("huge.png");
    for (int image = 0; image < 5000; ++image) {
        builder.json()["images"].push_back({{"uri", "huge.png"}});
    }
    builder.writeGltf(dir, "slow");
}

TEST(BatchRobustnessTest, AModelPastTheTimeLimitIsAbandonedAndTheBatchGoesOn) {
    const fs::path input = makeCollection("batch-timeout", 2, 4);
    fs::remove(input / "broken.gltf");
    writeSlowModel(input);
    const fs::path output = makeTempDir("batch-timeout-output");
    // Ten seconds: far more than the small models take on a busy 2-core machine (their first
    // upload compiles the pipelines), far less than the slow file's minutes.
    const CommandResult result = runEncore(batchArguments(
        input, output,
        "--views 2 --size 32 --samples 1 --max-texture-size 16 --model-timeout 10 --quiet"));
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("2 rendered, 1 failed"), std::string::npos) << result.out;
    const auto failures = jsonLines(output / "failures.jsonl");
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0]["stage"], "timeout");
    EXPECT_NE(failures[0]["file"].get<std::string>().find("slow.gltf"), std::string::npos);
    EXPECT_NE(failures[0]["error"].get<std::string>().find("time limit (10 s)"), std::string::npos)
        << failures[0]["error"];
    for (const char* model : {"set0/model", "set1/model"}) {
        EXPECT_TRUE(fs::exists(output / model / "transforms.json")) << model;
        EXPECT_TRUE(fs::exists(output / model / "001.png")) << model;
    }
    EXPECT_FALSE(fs::exists(output / "slow" / "transforms.json"));
}

// A millisecond is less than any model takes to load and upload: whichever stage notices (the
// loader's watchdog or the device thread after the upload), every model fails as a timeout, no
// file of theirs is left, and the process ends as usual.
TEST(BatchRobustnessTest, ALimitShorterThanEveryModelFailsThemAllAsTimeouts) {
    const fs::path input = makeCollection("batch-timeout-all", 3, 40);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-timeout-all-output");
    const CommandResult result = runEncore(batchArguments(
        input, output, "--views 2 --size 32 --samples 1 --model-timeout 0.001 --quiet"));
    EXPECT_EQ(result.exitCode, 1) << result.out << result.err;
    EXPECT_NE(result.out.find("0 rendered, 3 failed"), std::string::npos) << result.out;
    const auto failures = jsonLines(output / "failures.jsonl");
    ASSERT_EQ(failures.size(), 3u);
    for (const nlohmann::json& failure : failures) {
        EXPECT_EQ(failure["stage"], "timeout") << failure;
        EXPECT_NE(failure["error"].get<std::string>().find("(0.001 s"), std::string::npos)
            << failure;
    }
    EXPECT_TRUE(filesUnder(output, ".png").empty());
    EXPECT_TRUE(filesUnder(output, ".json").empty());
}

TEST(BatchRobustnessTest, LargeTexturesAreDownscaledWhileLoadingAndRecorded) {
    const fs::path input = makeTempDir("batch-max-texture");
    // Not a power of two, wider than high: the aspect ratio is kept.
    ASSERT_TRUE(
        writeFile(input / "wide.png", encodePngBytes(solidImage({200, 40, 40, 255}, 600, 300)))
            .ok());
    texturedQuad("wide.png").writeGltf(input, "quad");
    const fs::path output = makeTempDir("batch-max-texture-output");
    const CommandResult small = runEncore(batchArguments(
        input, output / "small", "--views 1 --size 32 --samples 1 --max-texture-size 256 --quiet"));
    ASSERT_EQ(small.exitCode, 0) << small.out << small.err;
    const nlohmann::json metadata = readJson(output / "small" / "quad" / "metadata.json");
    ASSERT_EQ(metadata["imagesDownscaled"].size(), 1u) << metadata.dump(2);
    const nlohmann::json& image = metadata["imagesDownscaled"][0];
    EXPECT_EQ(image["index"], 0);
    EXPECT_EQ(image["name"], "wide.png");
    EXPECT_EQ(image["originalWidth"], 600);
    EXPECT_EQ(image["originalHeight"], 300);
    EXPECT_EQ(image["width"], 256);
    EXPECT_EQ(image["height"], 128);

    // Wider than Encore decodes whole (16384): decoded row by row, drawn, recorded.
    ASSERT_TRUE(
        writeFile(input / "long.png", encodePngBytes(solidImage({40, 200, 40, 255}, 20000, 40)))
            .ok());
    texturedQuad("long.png").writeGltf(input, "long");
    const CommandResult longer = runEncore(batchArguments(
        input, output / "long", "--views 1 --size 32 --samples 1 --max-texture-size 1000 --quiet"));
    ASSERT_EQ(longer.exitCode, 0) << longer.out << longer.err;
    const nlohmann::json strip = readJson(output / "long" / "long" / "metadata.json");
    ASSERT_EQ(strip["imagesDownscaled"].size(), 1u) << strip.dump(2);
    EXPECT_EQ(strip["imagesDownscaled"][0]["originalWidth"], 20000);
    EXPECT_EQ(strip["imagesDownscaled"][0]["width"], 1000);
    EXPECT_EQ(strip["imagesDownscaled"][0]["height"], 2);
    EXPECT_TRUE(strip["imagesFailed"].empty()) << strip.dump(2);
    fs::remove(input / "long.gltf");

    // The default limit (4096) keeps it; a solid colour looks the same at either size.
    const CommandResult kept = runEncore(
        batchArguments(input, output / "kept", "--views 1 --size 32 --samples 1 --quiet"));
    ASSERT_EQ(kept.exitCode, 0) << kept.err;
    EXPECT_TRUE(readJson(output / "kept" / "quad" / "metadata.json")["imagesDownscaled"].empty());
    EXPECT_EQ(readBytes(output / "kept" / "quad" / "000.png"),
              readBytes(output / "small" / "quad" / "000.png"));
}

TEST(BatchRobustnessTest, ALostDeviceIsCreatedAgainAndTheModelsInFlightAreDrawnAgain) {
    const fs::path input = makeCollection("batch-device-loss", 4, 4);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-device-loss-output");
    const std::string options = "--views 3 --size 32 --samples 1 --quiet";
    const CommandResult reference = runEncore(batchArguments(input, output / "reference", options));
    ASSERT_EQ(reference.exitCode, 0) << reference.err;

    // Lost right after the third model's upload, while the first two may still be on the GPU.
    ::setenv("ENCORE_TEST_LOSE_DEVICE_AT_MODEL", "3", 1);
    const CommandResult lost = runEncore(batchArguments(input, output / "lost", options));
    ::unsetenv("ENCORE_TEST_LOSE_DEVICE_AT_MODEL");
    EXPECT_EQ(lost.exitCode, 0) << lost.out << lost.err;
    EXPECT_NE(
        lost.err.find("The GPU device was lost and created again; models in flight drawn again"),
        std::string::npos)
        << lost.err;
    EXPECT_NE(lost.out.find("4 rendered, 0 failed"), std::string::npos) << lost.out;
    EXPECT_TRUE(jsonLines(output / "lost" / "failures.jsonl").empty());
    EXPECT_TRUE(batchOutputFiles(output / "lost") == batchOutputFiles(output / "reference"))
        << "the models drawn again differ from those of a run without the loss";
}

}  // namespace
}  // namespace encore::test
