// What varies between the models and views of a batch, and what it records (issue 29): lighting
// from a folder of environments, drawn per model and switched between models exactly as a fixed
// environment would light them; cameras and lighting drawn from the seed and the model's name,
// so a re-ordered run writes the same bytes and another seed other ones; metadata.json and its
// blank views (failures with --strict); the Objaverse layout's camera matrices.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "BatchOutput.h"
#include "GeneratedModels.h"
#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "HdrFiles.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "batch/BatchRenderer.h"
#include "batch/ObjaverseCamera.h"
#include "core/FileIO.h"
#include "core/Sha256.h"
#include "encore/batch/Batch.h"
#include "encore/image/HdrImage.h"
#include "scene/SceneGenerator.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

std::string readBytes(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    return bytes.str();
}

nlohmann::json readJson(const fs::path& path) {
    return nlohmann::json::parse(readBytes(path), nullptr, false);
}

// Red, green and blue skies over grey ground.
fs::path environmentFolder(const fs::path& dir) {
    fs::create_directories(dir);
    test::writeHdr(dir / "red.hdr", {3.0f, 0.3f, 0.3f}, {0.4f, 0.4f, 0.4f});
    test::writeHdr(dir / "green.hdr", {0.3f, 3.0f, 0.3f}, {0.4f, 0.4f, 0.4f});
    test::writeHdr(dir / "blue.hdr", {0.3f, 0.3f, 3.0f}, {0.4f, 0.4f, 0.4f});
    return dir;
}

BatchOptions smallBatch(const fs::path& output) {
    BatchOptions options;
    options.output = output;
    options.width = 32;
    options.height = 32;
    options.samples = 1;
    options.views.views = 2;
    options.jobs = 2;
    options.renderer.environmentOptions = test::testEnvironmentOptions();
    return options;
}

// The files of one model's folder with their bytes.
std::map<std::string, std::string> imagesOf(const fs::path& folder) {
    std::map<std::string, std::string> images;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.path().extension() == ".png") {
            images[entry.path().filename().string()] = readBytes(entry.path());
        }
    }
    return images;
}

// Each model is lit by the environment drawn for it, turned and scaled as drawn: its images are
// those of a batch lit by that one file with that rotation and intensity, byte for byte, with
// one renderer or several (which switch environments between their models), and each file's
// maps are computed once.
TEST(BatchVariationTest, EachModelIsLitByItsDrawnEnvironmentAsAFixedOneWouldLightIt) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-environments");
    const std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 6);
    const fs::path environments = environmentFolder(dir / "skies");

    std::map<std::string, std::string> written[2];
    std::map<std::string, ModelLighting> lit;  // By model.
    for (const std::size_t renderers : {1, 3}) {
        BatchOptions options = smallBatch(dir / ("varied" + std::to_string(renderers)));
        options.renderers = renderers;
        options.views.seed = 11;
        options.lighting.environmentDirectory = environments;
        options.lighting.rotationDegrees = ValueRange(0.0f, 360.0f);
        options.lighting.intensity = ValueRange(0.5f, 1.5f);
        BatchRenderer batchRenderer(*context);
        auto summary = runBatch(batchRenderer, inputs, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        ASSERT_EQ(summary->rendered, inputs.size());
        written[renderers == 1 ? 0 : 1] = test::batchOutputFiles(options.output);

        std::set<std::string> files;
        for (const BatchInput& input : inputs) {
            const nlohmann::json transforms =
                readJson(options.output / input.name / "transforms.json");
            ASSERT_FALSE(transforms.is_discarded());
            ModelLighting lighting;
            lighting.environment = transforms["frames"][0]["environment"];
            lighting.rotationDegrees = transforms["frames"][0]["rotation"].get<float>();
            lighting.intensity = transforms["frames"][0]["intensity"].get<float>();
            for (const auto& frame : transforms["frames"]) {
                EXPECT_EQ(frame["environment"], lighting.environment);
                EXPECT_EQ(frame["rotation"], transforms["frames"][0]["rotation"]);
            }
            EXPECT_GE(lighting.rotationDegrees, 0.0f);
            EXPECT_LT(lighting.rotationDegrees, 360.0f);
            EXPECT_GE(lighting.intensity, 0.5f);
            EXPECT_LE(lighting.intensity, 1.5f);
            files.insert(lighting.environment);
            lit[input.name] = lighting;
        }
        EXPECT_GE(files.size(), 2u) << "every model drew the same environment";
        // The studio environment the renderers were built with, then each file once.
        EXPECT_EQ(batchRenderer.counts().environments, 1 + files.size());
    }
    EXPECT_TRUE(written[0] == written[1]) << "one renderer and three wrote other files";

    // Each model again, alone, with its file, rotation and intensity fixed.
    for (const BatchInput& input : inputs) {
        const ModelLighting& lighting = lit[input.name];
        BatchOptions options = smallBatch(dir / "fixed" / input.name);
        auto panorama = image::readHdr(environments / lighting.environment);
        ASSERT_TRUE(panorama.ok());
        options.renderer.environmentImage = std::make_shared<image::HdrImage>(std::move(*panorama));
        options.lighting.rotationDegrees = lighting.rotationDegrees;
        options.lighting.intensity = lighting.intensity;
        auto summary = runBatch(*context, std::vector<BatchInput>{input}, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        ASSERT_EQ(summary->rendered, 1u);
        EXPECT_TRUE(imagesOf(options.output / input.name) == imagesOf(dir / "varied1" / input.name))
            << input.name << " lit by " << lighting.environment << " differs";
    }
    EXPECT_TRUE(context->checkNoErrors("the lit batches").ok());
}

// More files than BatchRenderer keeps: the models lit by one file are rendered one after the
// other, so each file's maps are still computed once per run, and the order changes no byte.
TEST(BatchVariationTest, ModelsAreGroupedByEnvironmentSoEachFileIsBuiltOnce) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-grouped");
    const std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 16);
    const fs::path skies = dir / "skies";
    fs::create_directories(skies);
    const std::size_t files = kEnvironmentCacheSize + 4;
    for (std::size_t i = 0; i < files; ++i) {
        const float shade = 0.2f + 0.1f * float(i);
        test::writeHdr(skies / ("sky" + std::to_string(10 + i) + ".hdr"),
                       {shade, 1.0f, 2.0f - shade}, {0.3f, 0.3f, 0.3f}, 16);
    }
    BatchOptions options = smallBatch(dir / "out");
    options.views.views = 1;
    options.width = options.height = 8;
    options.lighting.environmentDirectory = skies;
    BatchRenderer batchRenderer(*context);
    auto summary = runBatch(batchRenderer, inputs, options);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    ASSERT_EQ(summary->rendered, inputs.size());
    std::set<std::string> used;
    for (const BatchInput& input : inputs) {
        used.insert(
            readJson(options.output / input.name / "transforms.json")["frames"][0]["environment"]
                .get<std::string>());
    }
    ASSERT_GT(used.size(), kEnvironmentCacheSize) << "too few files drawn to test the cache";
    EXPECT_EQ(batchRenderer.counts().environments, 1 + used.size());

    // In the opposite order: the same files.
    BatchOptions reversed = options;
    reversed.output = dir / "reversed";
    ASSERT_TRUE(
        runBatch(*context, std::vector<BatchInput>(inputs.rbegin(), inputs.rend()), reversed).ok());
    EXPECT_TRUE(test::batchOutputFiles(options.output) == test::batchOutputFiles(reversed.output));
}

// Everything random at once: directions on the upper hemisphere, jitter, distances, fields of
// view, environments, rotations and intensities. The same seed writes the same bytes, in any
// order of the models; another seed draws other views and lighting.
TEST(BatchVariationTest, TheSeedAndTheNamesDecideEveryDrawWhateverTheOrder) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-seed");
    const std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 4);
    const fs::path environments = environmentFolder(dir / "skies");
    const auto varied = [&](const fs::path& output, std::uint64_t seed) {
        BatchOptions options = smallBatch(output);
        options.views.seed = seed;
        options.views.distribution = CameraDistribution::UpperHemisphere;
        options.views.jitterDegrees = 5.0f;
        options.views.distance = ValueRange(1.5f, 2.2f);
        options.views.horizontalFovDegrees = ValueRange(35.0f, 55.0f);
        options.lighting.environmentDirectory = environments;
        options.lighting.rotationDegrees = ValueRange(0.0f, 360.0f);
        options.lighting.intensity = ValueRange(0.5f, 1.5f);
        return options;
    };
    const BatchOptions first = varied(dir / "first", 5);
    ASSERT_TRUE(runBatch(*context, inputs, first).ok());
    std::vector<BatchInput> reversed(inputs.rbegin(), inputs.rend());
    const BatchOptions again = varied(dir / "again", 5);
    ASSERT_TRUE(runBatch(*context, reversed, again).ok());
    const BatchOptions other = varied(dir / "other", 6);
    ASSERT_TRUE(runBatch(*context, inputs, other).ok());

    const auto a = test::batchOutputFiles(first.output);
    EXPECT_EQ(a.size(), inputs.size() * (2 + 2));
    EXPECT_TRUE(a == test::batchOutputFiles(again.output)) << "the same seed, other bytes";
    for (const BatchInput& input : inputs) {
        const nlohmann::json one = readJson(first.output / input.name / "transforms.json");
        const nlohmann::json two = readJson(other.output / input.name / "transforms.json");
        EXPECT_NE(one["frames"][0]["transform_matrix"], two["frames"][0]["transform_matrix"]);
        EXPECT_NE(one["frames"][0]["rotation"], two["frames"][0]["rotation"]);
        EXPECT_NE(readBytes(first.output / input.name / "000.png"),
                  readBytes(other.output / input.name / "000.png"));
        // Each frame keeps its own field of view, within the range, and every eye is above the
        // horizon.
        for (const auto& frame : one["frames"]) {
            const double fov = frame["camera_angle_x"].get<double>();
            EXPECT_GE(fov, glm::radians(35.0) - 1e-6);
            EXPECT_LE(fov, glm::radians(55.0) + 1e-6);
            EXPECT_NEAR(frame["fl_x"].get<double>(), 16.0 / std::tan(0.5 * fov), 1e-6);
            // Jitter may take an eye on the horizon at most 5 degrees below it.
            const double height = frame["transform_matrix"][1][3].get<double>();
            EXPECT_GT(height, -2.2 * std::sin(glm::radians(5.0)));
        }
    }
}

// A model far outside every view (not normalised) renders blank: metadata.json lists its views
// as blankViews and the batch finishes it; with --strict it fails with stage "blank" and leaves
// no file. A model in view has no blank view.
TEST(BatchVariationTest, BlankViewsAreListedAndFailTheModelWithStrict) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-blank");
    fs::create_directories(dir / "in");
    const auto quadAt = [&](const std::string& name, const glm::vec3& where) {
        test::GltfBuilder builder;
        const auto positions = builder.addPositions(
            {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}});
        const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        const auto material = builder.addMaterial({.doubleSided = true});
        const auto mesh = builder.addMesh(
            {.attributes = {{"POSITION", positions}}, .indices = indices, .material = material});
        builder.addScene({builder.addNode({.mesh = mesh, .translation = where})});
        return BatchInput{builder.writeGlb(dir / "in", name), name};
    };
    const std::vector<BatchInput> inputs = {quadAt("far", {100.0f, 0.0f, 0.0f}),
                                            quadAt("near", glm::vec3(0.0f))};
    BatchOptions options = smallBatch(dir / "out");
    options.views.normalize = false;
    options.views.elevationDegrees = 0.0f;
    auto summary = runBatch(*context, inputs, options);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(summary->rendered, 2u);
    EXPECT_EQ(summary->failed, 0u);
    const nlohmann::json far = readJson(options.output / "far" / "metadata.json");
    ASSERT_FALSE(far.is_discarded());
    EXPECT_EQ(far["blankViews"], nlohmann::json::parse("[0, 1]"));
    EXPECT_EQ(far["coveredPixels"], nlohmann::json::parse("[0, 0]"));
    EXPECT_EQ(far["blankThreshold"], 1);
    const nlohmann::json near = readJson(options.output / "near" / "metadata.json");
    EXPECT_EQ(near["blankViews"], nlohmann::json::array());
    EXPECT_GT(near["coveredPixels"][0].get<int>(), 50);
    EXPECT_GT(near["coveredPixels"][1].get<int>(), 50);

    // A threshold above what the near quad covers makes its views blank too.
    BatchOptions demanding = smallBatch(dir / "demanding");
    demanding.views = options.views;
    demanding.blankThreshold = 32 * 32;
    ASSERT_TRUE(runBatch(*context, std::vector<BatchInput>{inputs[1]}, demanding).ok());
    EXPECT_EQ(readJson(demanding.output / "near" / "metadata.json")["blankViews"],
              nlohmann::json::parse("[0, 1]"));

    BatchOptions strict = smallBatch(dir / "strict");
    strict.views = options.views;
    strict.strict = true;
    summary = runBatch(*context, inputs, strict);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    EXPECT_EQ(summary->rendered, 1u);
    ASSERT_EQ(summary->failures.size(), 1u);
    EXPECT_EQ(summary->failures[0].file, inputs[0].path);
    EXPECT_EQ(summary->failures[0].stage, "blank");
    EXPECT_NE(summary->failures[0].error.find("is blank: 0 of its 1024 pixels are covered"),
              std::string::npos)
        << summary->failures[0].error;
    EXPECT_NE(readBytes(strict.output / "failures.jsonl").find("\"stage\":\"blank\""),
              std::string::npos);
    for (const char* file : {"000.png", "001.png", "metadata.json", "transforms.json"}) {
        EXPECT_FALSE(fs::exists(strict.output / "far" / file)) << file;
    }
    EXPECT_TRUE(fs::exists(strict.output / "near" / "transforms.json"));

    // With a colour background there is no alpha to count coverage by.
    BatchOptions opaque = smallBatch(dir / "opaque");
    opaque.views = options.views;
    opaque.renderer.toneMapping.background = render::BackgroundKind::Color;
    ASSERT_TRUE(runBatch(*context, std::vector<BatchInput>{inputs[0]}, opaque).ok());
    const nlohmann::json unknown = readJson(opaque.output / "far" / "metadata.json");
    EXPECT_TRUE(unknown["blankViews"].is_null());
    EXPECT_TRUE(unknown["coveredPixels"].is_null());
}

// The 3x4 matrix of a .npy file written by npyFloat64.
std::array<double, 12> readCameraMatrix(const fs::path& path) {
    const std::string bytes = readBytes(path);
    std::array<double, 12> values{};
    EXPECT_EQ(bytes.size(), 128u + sizeof(values)) << path;
    if (bytes.size() == 128u + sizeof(values)) {
        std::memcpy(values.data(), bytes.data() + 128, sizeof(values));
    }
    return values;
}

// --layout objaverse: a 000.npy per view holding the camera of transforms.json in the Objaverse
// scripts' convention, part of the model's files (a missing one makes the model render again);
// metadata.json describes the file.
TEST(BatchVariationTest, ObjaverseLayoutWritesACameraMatrixPerView) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-objaverse");
    std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 1);
    const auto models = test::sharedModelsDir();
    const fs::path box =
        models ? *models / "BoxTextured" / "glTF-Binary" / "BoxTextured.glb" : fs::path();
    if (models && fs::exists(box)) {
        inputs.push_back({box, "BoxTextured"});
    }
    BatchOptions options = smallBatch(dir / "out");
    options.layout = OutputLayout::Objaverse;
    options.views.distribution = CameraDistribution::Sphere;
    options.views.views = 3;
    auto summary = runBatch(*context, inputs, options);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    ASSERT_EQ(summary->rendered, inputs.size());
    for (const BatchInput& input : inputs) {
        const fs::path folder = options.output / input.name;
        const nlohmann::json transforms = readJson(folder / "transforms.json");
        for (int view = 0; view < 3; ++view) {
            glm::mat4 cameraToWorld;
            for (int row = 0; row < 4; ++row) {
                for (int column = 0; column < 4; ++column) {
                    cameraToWorld[column][row] =
                        transforms["frames"][view]["transform_matrix"][row][column].get<float>();
                }
            }
            const auto expected = objaverseCameraMatrix(cameraToWorld);
            const auto written = readCameraMatrix(folder / ("00" + std::to_string(view) + ".npy"));
            for (std::size_t i = 0; i < 12; ++i) {
                EXPECT_NEAR(written[i], expected[i], 1e-6) << input.name << " view " << view;
            }
        }
        const nlohmann::json metadata = readJson(folder / "metadata.json");
        auto bytes = readFile(input.path);
        ASSERT_TRUE(bytes.ok());
        EXPECT_EQ(metadata["sha256"], Sha256::hex(*bytes));
        EXPECT_EQ(metadata["fileBytes"], bytes->size());
        EXPECT_EQ(metadata["coveredPixels"].size(), 3u);
        EXPECT_GT(metadata["seconds"]["load"].get<double>(), 0.0);  // Parsing took time.
        if (input.name == "BoxTextured") {
            EXPECT_EQ(metadata["triangles"], 12);
            EXPECT_EQ(metadata["vertices"], 24);
            EXPECT_EQ(metadata["textures"], 1);
        }
    }
    // Without one matrix the model is not finished: a rerun renders it again.
    fs::remove(options.output / inputs[0].name / "001.npy");
    summary = runBatch(*context, inputs, options);
    ASSERT_TRUE(summary.ok());
    EXPECT_EQ(summary->rendered, 1u);
    EXPECT_EQ(summary->skipped, inputs.size() - 1);
    EXPECT_TRUE(fs::exists(options.output / inputs[0].name / "001.npy"));
}

// A folder that does not hold environments stops the batch before anything renders.
TEST(BatchVariationTest, ABadEnvironmentFolderIsRefused) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-variation-bad-folder");
    const std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 1);
    BatchOptions options = smallBatch(dir / "out");
    options.lighting.environmentDirectory = dir / "in";  // Models, no .hdr.
    auto summary = runBatch(*context, inputs, options);
    ASSERT_FALSE(summary.ok());
    EXPECT_EQ(summary.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(summary.error().message.find("holds no Radiance .hdr file"), std::string::npos);
    EXPECT_FALSE(fs::exists(options.output));
}

}  // namespace
}  // namespace encore::batch
