// encore batch's dataset options (issue 29): cameras and lighting drawn from the seed and
// recorded per frame, the same bytes for the same seed; --layout objaverse's camera matrices;
// metadata.json and blank views (failures with --strict); and every bad value a usage error
// before anything renders.

#include <gtest/gtest.h>

#include <chrono>

#include <cmath>
#include <fstream>
#include <set>

#include "BatchCommandSupport.h"
#include "BatchOutput.h"
#include "CommandRunner.h"
#include "GltfBuilder.h"
#include "HdrFiles.h"
#include "TestPaths.h"
#include "core/FileIO.h"
#include "core/Sha256.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const fs::path& path) {
    return nlohmann::json::parse(readBytes(path), nullptr, false);
}

// Two generated models and a folder of two environments beside them.
struct Dataset {
    fs::path input;
    fs::path environments;
};

Dataset makeDataset(const std::string& name) {
    Dataset dataset;
    dataset.input = makeCollection(name, 2, 4);
    fs::remove(dataset.input / "broken.gltf");
    dataset.environments = makeTempDir(name + "-skies");
    writeHdr(dataset.environments / "dawn.hdr", {2.0f, 0.8f, 0.4f}, {0.3f, 0.3f, 0.3f});
    writeHdr(dataset.environments / "noon.hdr", {0.6f, 0.8f, 2.0f}, {0.4f, 0.4f, 0.4f});
    return dataset;
}

TEST(BatchDatasetTest, CamerasAndLightingAreDrawnFromTheSeedAndRecordedPerFrame) {
    const Dataset dataset = makeDataset("batch-dataset-varied");
    const fs::path output = makeTempDir("batch-dataset-varied-output");
    const std::string varied =
        "--views 3 --size 32 --samples 1 --camera-distribution upper-hemisphere "
        "--distance 1.5:2.2 --fov 30:60 --camera-jitter 5 --environment-dir " +
        quote(dataset.environments.string()) +
        " --environment-rotation random --environment-intensity 0.5:1.5 --quiet";
    for (const char* run : {"a", "b"}) {
        const CommandResult result =
            runEncore(batchArguments(dataset.input, output / run, varied + " --seed 3"));
        ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    }
    const CommandResult other =
        runEncore(batchArguments(dataset.input, output / "c", varied + " --seed 4"));
    ASSERT_EQ(other.exitCode, 0) << other.err;

    const auto a = batchOutputFiles(output / "a");
    EXPECT_EQ(a.size(), 2u * (3 + 2));
    EXPECT_TRUE(a == batchOutputFiles(output / "b")) << "the same seed wrote other bytes";
    std::set<std::string> environments;
    for (const char* model : {"set0/model", "set1/model"}) {
        const nlohmann::json transforms = readJson(output / "a" / model / "transforms.json");
        ASSERT_FALSE(transforms.is_discarded());
        EXPECT_FALSE(transforms.contains("camera_angle_x")) << "fields of view differ per frame";
        for (const auto& frame : transforms["frames"]) {
            const double fov = frame["camera_angle_x"].get<double>();
            EXPECT_GE(fov, 30.0 * M_PI / 180.0 - 1e-6);
            EXPECT_LE(fov, 60.0 * M_PI / 180.0 + 1e-6);
            EXPECT_NEAR(frame["fl_x"].get<double>(), 16.0 / std::tan(0.5 * fov), 1e-6);
            EXPECT_EQ(frame["w"], 32);
            const auto& m = frame["transform_matrix"];
            const double distance =
                std::hypot(m[0][3].get<double>(), m[1][3].get<double>(), m[2][3].get<double>());
            EXPECT_GE(distance, 1.5 - 1e-4);
            EXPECT_LE(distance, 2.2 + 1e-4);
            EXPECT_GT(m[1][3].get<double>(), -distance * std::sin(5.0 * M_PI / 180.0) - 1e-4);
            EXPECT_EQ(frame["environment"], transforms["frames"][0]["environment"]);
            EXPECT_GE(frame["rotation"].get<double>(), 0.0);
            EXPECT_LT(frame["rotation"].get<double>(), 360.0);
            EXPECT_GE(frame["intensity"].get<double>(), 0.5);
            EXPECT_LE(frame["intensity"].get<double>(), 1.5);
        }
        environments.insert(transforms["frames"][0]["environment"].get<std::string>());
        const nlohmann::json seeded = readJson(output / "c" / model / "transforms.json");
        EXPECT_NE(seeded["frames"][0]["transform_matrix"],
                  transforms["frames"][0]["transform_matrix"]);
        EXPECT_NE(seeded["frames"][0]["rotation"], transforms["frames"][0]["rotation"]);
        EXPECT_NE(readBytes(output / "c" / model / "000.png"),
                  readBytes(output / "a" / model / "000.png"));
    }
    for (const std::string& environment : environments) {
        EXPECT_TRUE(environment == "dawn.hdr" || environment == "noon.hdr") << environment;
    }
}

// Without options every frame still records the lighting: the built-in studio, or the file
// --environment names, with the rotation and intensity given.
TEST(BatchDatasetTest, FixedLightingIsRecordedToo) {
    const Dataset dataset = makeDataset("batch-dataset-fixed");
    const fs::path output = makeTempDir("batch-dataset-fixed-output");
    ASSERT_EQ(runEncore(batchArguments(dataset.input, output / "studio",
                                       "--views 1 --size 16 --samples 1 --quiet"))
                  .exitCode,
              0);
    const nlohmann::json studio = readJson(output / "studio/set0/model/transforms.json");
    EXPECT_EQ(studio["frames"][0]["environment"], "studio");
    EXPECT_EQ(studio["frames"][0]["rotation"], 0.0);
    EXPECT_EQ(studio["frames"][0]["intensity"], 1.0);
    const fs::path noon = dataset.environments / "noon.hdr";
    const CommandResult lit = runEncore(
        batchArguments(dataset.input, output / "noon",
                       "--views 1 --size 16 --samples 1 --environment " + quote(noon.string()) +
                           " --environment-rotation 90 --environment-intensity 2 --quiet"));
    ASSERT_EQ(lit.exitCode, 0) << lit.err;
    const nlohmann::json fixed = readJson(output / "noon/set1/model/transforms.json");
    EXPECT_EQ(fixed["frames"][0]["environment"], noon.string());
    EXPECT_EQ(fixed["frames"][0]["rotation"], 90.0);
    EXPECT_EQ(fixed["frames"][0]["intensity"], 2.0);
    EXPECT_NE(readBytes(output / "noon/set1/model/000.png"),
              readBytes(output / "studio/set1/model/000.png"));
}

TEST(BatchDatasetTest, ObjaverseLayoutWritesNumpyCameraMatricesAndMetadata) {
    const Dataset dataset = makeDataset("batch-dataset-objaverse");
    const fs::path output = makeTempDir("batch-dataset-objaverse-output");
    const auto start = std::chrono::steady_clock::now();
    const CommandResult run = runEncore(batchArguments(
        dataset.input, output, "--views 2 --size 16 --samples 1 --layout objaverse --quiet"));
    const double wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    const fs::path model = output / "set0" / "model";
    for (const char* matrix : {"000.npy", "001.npy"}) {
        const std::string bytes = readBytes(model / matrix);
        ASSERT_EQ(bytes.size(), 128u + 12 * 8) << matrix;
        EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
        EXPECT_NE(bytes.find("'shape': (3, 4)"), std::string::npos);
    }
    const nlohmann::json metadata = readJson(model / "metadata.json");
    auto bytes = readFile(dataset.input / "set0" / "model.glb");
    ASSERT_TRUE(bytes.ok());
    EXPECT_EQ(metadata["sha256"], Sha256::hex(*bytes));
    EXPECT_EQ(metadata["instances"], 4);
    EXPECT_GT(metadata["triangles"].get<int>(), 4);
    EXPECT_EQ(metadata["name"], "set0/model");
    // The model's stages took time, and no more than the whole run.
    double stages = 0.0;
    for (const char* stage : {"load", "upload", "render", "encode"}) {
        stages += metadata["seconds"][stage].get<double>();
        EXPECT_LE(metadata["seconds"][stage].get<double>(), wallSeconds) << stage;
    }
    EXPECT_GT(metadata["seconds"]["load"].get<double>(), 0.0);
    EXPECT_LE(stages, wallSeconds);
    // The default layout writes none, and a rerun with the layout needs them.
    const CommandResult nerf =
        runEncore(batchArguments(dataset.input, output / "nerf", "--views 2 --size 16 --quiet"));
    ASSERT_EQ(nerf.exitCode, 0);
    EXPECT_TRUE(filesUnder(output / "nerf", ".npy").empty());
    const CommandResult upgraded = runEncore(batchArguments(
        dataset.input, output / "nerf", "--views 2 --size 16 --layout objaverse --quiet"));
    EXPECT_NE(upgraded.out.find("2 rendered, 0 failed, 0 skipped"), std::string::npos)
        << upgraded.out;
}

// A quad far from the origin, not normalised: the cameras around the origin see nothing.
TEST(BatchDatasetTest, BlankViewsAreRecordedAndFailTheModelWithStrict) {
    const fs::path input = makeTempDir("batch-dataset-blank");
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", positions}}, .indices = indices});
    builder.addScene({builder.addNode({.mesh = mesh, .translation = glm::vec3(0, 500, 0)})});
    builder.writeGlb(input, "far");
    const fs::path output = makeTempDir("batch-dataset-blank-output");
    const std::string common = "--views 2 --size 16 --samples 1 --no-normalize --quiet";
    const CommandResult listed = runEncore(batchArguments(input, output / "listed", common));
    ASSERT_EQ(listed.exitCode, 0) << listed.out << listed.err;
    const nlohmann::json metadata = readJson(output / "listed/far/metadata.json");
    EXPECT_EQ(metadata["blankViews"], nlohmann::json::parse("[0, 1]"));

    const CommandResult strict =
        runEncore(batchArguments(input, output / "strict", common + " --strict"));
    EXPECT_EQ(strict.exitCode, 1) << strict.out;
    const auto failures = jsonLines(output / "strict" / "failures.jsonl");
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0]["stage"], "blank");
    EXPECT_NE(failures[0]["error"].get<std::string>().find("is blank: 0 of its 256 pixels"),
              std::string::npos)
        << failures[0]["error"];
    EXPECT_FALSE(fs::exists(output / "strict/far/transforms.json"));
    EXPECT_TRUE(filesUnder(output / "strict", ".png").empty());

    // No view is blank below a threshold of 0.
    const CommandResult lenient = runEncore(
        batchArguments(input, output / "lenient", common + " --strict --blank-threshold 0"));
    EXPECT_EQ(lenient.exitCode, 0) << lenient.out << lenient.err;
}

// Each bad value: exit 2, a message naming what is wrong, and no model rendered.
TEST(BatchDatasetTest, BadValuesAreUsageErrors) {
    const Dataset dataset = makeDataset("batch-dataset-bad");
    const fs::path output = makeTempDir("batch-dataset-bad-output");
    const fs::path hdr = dataset.environments / "dawn.hdr";
    const std::string folder = quote(dataset.environments.string());
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--distance 2:1", "camera distance (2 to 1)"},
        {"--distance far", "--distance takes a number or a range MIN:MAX (not 'far')"},
        {"--distance 0", "must be positive"},
        {"--fov 0:40", "field of view (0 to 40 degrees) must lie in (0, 180)"},
        {"--fov 30:", "--fov takes a number or a range"},
        {"--camera-distribution cube", "--camera-distribution"},
        {"--random-views 3 --camera-distribution orbit", "excludes"},
        {"--camera-jitter 200", "--camera-jitter"},
        {"--environment-dir " + quote((output / "absent").string()), "is not a folder"},
        {"--environment-dir " + quote(dataset.input.string()), "holds no Radiance .hdr file"},
        {"--environment-dir " + folder + " --environment " + quote(hdr.string()), "excludes"},
        {"--environment-rotation sideways", "--environment-rotation takes a number"},
        {"--environment-rotation 90:10", "environment rotation (90 to 10 degrees)"},
        {"--environment-intensity -1", "environment intensity (-1) must be 0 or more"},
        {"--layout zip", "--layout"},
        {"--blank-threshold -3", "--blank-threshold"},
    };
    expectUsageErrors(dataset.input, output, "--views 1 --size 8 --quiet ", cases);
}

}  // namespace
}  // namespace encore::test
