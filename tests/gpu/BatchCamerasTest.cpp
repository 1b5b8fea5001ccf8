// The cameras of issue 50 rendered: an orthographic view of a unit cube draws parallel edges (its
// silhouette a square of the size --ortho-scale says, a side seen at an angle a band of one
// height), and a batch rendered again from the transforms.json it wrote (--poses) writes the
// same bytes, in every camera convention.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "BatchOutput.h"
#include "GeneratedModels.h"
#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "batch/PoseFile.h"
#include "core/FileIO.h"
#include "encore/batch/Batch.h"
#include "encore/image/ImageCodec.h"
#include "scene/SceneGenerator.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

// A cube from -1 to 1 (normalised into the unit box: sides of 1), one grey material.
BatchInput writeCube(const fs::path& dir) {
    test::GltfBuilder builder;
    const std::vector<glm::vec3> corners = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const std::vector<std::uint16_t> indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7,
                                                0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2,
                                                0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    const auto positions = builder.addPositions(corners);
    const auto index = builder.addIndices(indices);
    const auto material = builder.addMaterial({.baseColor = {0.5f, 0.5f, 0.5f, 1.0f}});
    const auto mesh = builder.addMesh(
        {{.attributes = {{"POSITION", positions}}, .indices = index, .material = material}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    fs::create_directories(dir);
    return {builder.writeGlb(dir, "cube"), "cube"};
}

BatchOptions tinyBatch(const fs::path& output) {
    BatchOptions options;
    options.output = output;
    options.width = 64;
    options.height = 64;
    options.samples = 1;
    options.jobs = 2;
    options.renderer.environmentOptions = test::testEnvironmentOptions();
    return options;
}

image::ImageRgba8 readImage(const fs::path& path) {
    auto bytes = readFile(path);
    EXPECT_TRUE(bytes.ok()) << path;
    auto image = image::decodeImage(*bytes);
    EXPECT_TRUE(image.ok()) << path;
    return std::move(*image);
}

// Covered pixels (alpha > 0) in each column.
std::vector<std::uint32_t> coveredPerColumn(const image::ImageRgba8& image) {
    std::vector<std::uint32_t> columns(image.width, 0);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            columns[x] += image.pixels[(std::size_t(y) * image.width + x) * 4 + 3] > 0 ? 1 : 0;
        }
    }
    return columns;
}

// An orthographic camera facing the cube draws its front face as a square 64 / scale pixels wide,
// every covered column of one height; turned 30 degrees, its vertical edges stay parallel (every
// covered column the same height) where a perspective camera draws the near edge taller.
TEST(BatchCamerasTest, AnOrthographicCubeHasParallelEdges) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-cameras-ortho");
    const BatchInput cube = writeCube(dir / "in");
    BatchOptions options = tinyBatch(dir / "ortho");
    options.views.projection = Projection::Orthographic;
    options.views.orthoScale = 2.0f;
    options.views.azimuthsDegrees = {0.0f, 30.0f};
    options.views.elevationsDegrees = {0.0f};
    auto summary = runBatch(*context, std::span(&cube, 1), options);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    ASSERT_EQ(summary->rendered, 1u);

    const std::vector<std::uint32_t> front =
        coveredPerColumn(readImage(options.output / "cube" / "000.png"));
    std::uint32_t columns = 0;
    for (std::uint32_t x = 0; x < front.size(); ++x) {
        if (front[x] > 0) {
            ++columns;
            EXPECT_EQ(front[x], 32u) << "column " << x;
            EXPECT_GE(x, 16u);
            EXPECT_LT(x, 48u);
        }
    }
    EXPECT_EQ(columns, 32u);  // A side of 1 in a view 2 wide: half of 64 pixels.

    const std::vector<std::uint32_t> turned =
        coveredPerColumn(readImage(options.output / "cube" / "001.png"));
    for (std::uint32_t x = 0; x < turned.size(); ++x) {
        if (turned[x] > 0) {
            EXPECT_EQ(turned[x], 32u) << "column " << x;
        }
    }

    // The same views in perspective: the turned cube's near edge is taller than its far one.
    BatchOptions perspective = tinyBatch(dir / "perspective");
    perspective.views.azimuthsDegrees = {30.0f};
    perspective.views.elevationsDegrees = {0.0f};
    perspective.layout = OutputLayout::Gobjaverse;  // And a camera file per view.
    summary = runBatch(*context, std::span(&cube, 1), perspective);
    ASSERT_TRUE(summary.ok()) << summary.error().message;
    const std::vector<std::uint32_t> heights =
        coveredPerColumn(readImage(perspective.output / "cube" / "000.png"));
    const auto [lowest, highest] =
        std::minmax_element(heights.begin(), heights.end(), [](std::uint32_t a, std::uint32_t b) {
            return (a == 0 ? 1000u : a) < (b == 0 ? 1000u : b);
        });
    EXPECT_GT(*std::max_element(heights.begin(), heights.end()), *lowest + 2u);
    (void)highest;
    const nlohmann::json cameraFile = nlohmann::json::parse(
        std::ifstream(perspective.output / "cube" / "000.json"), nullptr, false);
    ASSERT_TRUE(cameraFile.is_object());
    EXPECT_NEAR(cameraFile["x_fov"].get<double>(), glm::radians(kDefaultHorizontalFovDegrees),
                1e-6);
    EXPECT_NEAR(cameraFile["origin"][0].get<double>(), 1.5 * std::sin(glm::radians(30.0)), 1e-5);
    EXPECT_NEAR(cameraFile["z"][0].get<double>(), -std::sin(glm::radians(30.0)), 1e-5);
    // The camera files are part of a finished model: a rerun skips it, one fewer renders it.
    summary = runBatch(*context, std::span(&cube, 1), perspective);
    ASSERT_TRUE(summary.ok());
    EXPECT_EQ(summary->skipped, 1u);
    fs::remove(perspective.output / "cube" / "000.json");
    summary = runBatch(*context, std::span(&cube, 1), perspective);
    ASSERT_TRUE(summary.ok());
    EXPECT_EQ(summary->rendered, 1u);

    const nlohmann::json transforms = nlohmann::json::parse(
        std::ifstream(options.output / "cube" / "transforms.json"), nullptr, false);
    EXPECT_EQ(transforms["projection"], "orthographic");
    EXPECT_EQ(transforms["ortho_scale"], 2.0);
    EXPECT_FALSE(transforms.contains("camera_angle_x"));
    EXPECT_EQ(transforms["frames"][1]["projection"], "orthographic");
    const nlohmann::json metadata = nlohmann::json::parse(
        std::ifstream(options.output / "cube" / "metadata.json"), nullptr, false);
    EXPECT_EQ(metadata["camera"]["projection"], "orthographic");
    EXPECT_EQ(metadata["camera"]["orthoScale"], 2.0);
}

// Render, read the transforms.json written back as --poses, render again: the same files (the
// poses' metadata says where they came from), in each convention and projection.
TEST(BatchCamerasTest, PosesRoundTripToTheSameBytes) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("batch-cameras-poses");
    const std::vector<BatchInput> inputs = test::writeGeneratedModels(dir / "in", 1);
    struct Case {
        std::optional<CameraConvention> convention;
        Projection projection;
    };
    const Case cases[] = {{std::nullopt, Projection::Perspective},
                          {CameraConvention::OpenCv, Projection::Perspective},
                          {CameraConvention::Blender, Projection::Orthographic}};
    int index = 0;
    for (const Case& c : cases) {
        const std::string name = std::to_string(index++);
        BatchOptions first = tinyBatch(dir / ("first" + name));
        first.views.views = 3;
        first.views.distribution = CameraDistribution::Sphere;
        first.views.distance = ValueRange(1.5f, 2.2f);
        first.views.horizontalFovDegrees = ValueRange(30.0f, 60.0f);
        first.views.projection = c.projection;
        first.cameraConvention = c.convention;
        first.layout = OutputLayout::Objaverse;
        auto summary = runBatch(*context, inputs, first);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        ASSERT_EQ(summary->rendered, 1u);

        BatchOptions second = tinyBatch(dir / ("second" + name));
        second.cameraConvention = c.convention;
        second.layout = OutputLayout::Objaverse;
        const fs::path written = first.output / "m1" / "transforms.json";
        auto poses = readPoseFile(written, "--poses", c.convention, second.views);
        ASSERT_TRUE(poses.ok()) << poses.error().message;
        second.views.poses = *poses;
        second.views.posesFile = written.string();
        second.views.projection = c.projection;  // The depth scale's and metadata's.
        summary = runBatch(*context, inputs, second);
        ASSERT_TRUE(summary.ok()) << summary.error().message;

        auto firstFiles = test::batchOutputFiles(first.output);
        auto secondFiles = test::batchOutputFiles(second.output);
        ASSERT_EQ(firstFiles.size(), secondFiles.size());
        for (const auto& [file, bytes] : firstFiles) {
            if (file.ends_with("metadata.json")) {
                continue;  // It names where the cameras came from.
            }
            EXPECT_TRUE(bytes == secondFiles[file]) << "case " << name << ": " << file;
        }
        const nlohmann::json metadata = nlohmann::json::parse(
            std::ifstream(second.output / "m1" / "metadata.json"), nullptr, false);
        EXPECT_EQ(metadata["camera"]["poses"], written.string());
    }
}

}  // namespace
}  // namespace encore::batch
