// encore batch --point-cloud N (docs/batch.md#point-clouds): N points drawn by area from a cube's
// faces, in the normalised frame, with the faces' normals and the base colour, the same file for
// the same seed.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "BatchCommandSupport.h"
#include "CommandRunner.h"
#include "GltfBuilder.h"
#include "TestPaths.h"
#include "core/FileIO.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

constexpr glm::vec4 kColor{0.8f, 0.2f, 0.1f, 1.0f};

// A cube from -1 to 1 (normalised: -0.5 to 0.5), four vertices per face with its normal.
fs::path writeCube(const fs::path& dir) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<std::uint16_t> indices;
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 normal(0.0f);
            normal[axis] = sign;
            const glm::vec3 u(normal[1] != 0 || normal[2] != 0 ? 1.0f : 0.0f, normal[0] != 0, 0.0f);
            const glm::vec3 v = glm::cross(normal, u);
            const auto first = std::uint16_t(positions.size());
            for (const glm::vec2 corner :
                 {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
                positions.push_back(normal + corner.x * u + corner.y * v);
                normals.push_back(normal);
            }
            for (int i : {0, 1, 2, 0, 2, 3}) {
                indices.push_back(std::uint16_t(first + i));
            }
        }
    }
    GltfBuilder builder;
    const auto material = builder.addMaterial({.baseColor = kColor});
    const auto mesh =
        builder.addMesh({{{.attributes = {{"POSITION", builder.addPositions(positions)},
                                          {"NORMAL", builder.addNormals(normals)}},
                           .indices = builder.addIndices(indices),
                           .material = material}}},
                        "cube");
    builder.addScene({builder.addNode({.mesh = mesh, .name = "cube"})});
    fs::create_directories(dir);
    return builder.writeGlb(dir, "cube");
}

struct Point {
    float position[3];
    float normal[3];
    std::uint8_t color[4];
};

// The points of a binary little-endian PLY as PointCloud.h writes it; fails the test when the
// header is not that one.
std::vector<Point> readPly(const fs::path& path, std::uint32_t expectedCount) {
    const std::string bytes = readBytes(path);
    const std::string end = "end_header\n";
    const std::size_t body = bytes.find(end);
    EXPECT_NE(body, std::string::npos);
    const std::string header = bytes.substr(0, body);
    EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u) << header;
    EXPECT_NE(header.find("element vertex " + std::to_string(expectedCount) + "\n"),
              std::string::npos)
        << header;
    EXPECT_NE(header.find("property float nz\nproperty uchar red\n"), std::string::npos);
    std::vector<Point> points(expectedCount);
    EXPECT_EQ(bytes.size() - body - end.size(), std::size_t(expectedCount) * 28);
    for (std::uint32_t i = 0; i < expectedCount && body + end.size() + (i + 1) * 28 <= bytes.size();
         ++i) {
        const char* record = bytes.data() + body + end.size() + std::size_t(i) * 28;
        std::memcpy(points[i].position, record, 12);
        std::memcpy(points[i].normal, record + 12, 12);
        std::memcpy(points[i].color, record + 24, 4);
    }
    return points;
}

std::uint8_t srgbByte(float linear) {
    const double encoded =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return std::uint8_t(std::lround(encoded * 255.0));
}

TEST(BatchPointCloudTest, PointsLieOnTheCubesFacesWithTheirNormalsAndColour) {
    const fs::path input = writeCube(makeTempDir("point-cloud-input"));
    const fs::path output = makeTempDir("point-cloud-output");
    const std::string common = "--views 1 --size 16 --samples 1 --quiet --point-cloud 1200 ";
    for (const auto& [folder, seed] :
         {std::pair{"a", "7"}, std::pair{"b", "7"}, std::pair{"c", "8"}}) {
        const CommandResult run =
            runEncore(batchArguments(input, output / folder, common + "--seed " + seed));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    }
    const fs::path model = output / "a" / "cube";
    const std::vector<Point> points = readPly(model / "points.ply", 1200);
    ASSERT_EQ(points.size(), 1200u);
    std::array<int, 6> perFace{};
    for (const Point& point : points) {
        // On the face whose axis holds the largest coordinate, with that face's normal.
        int axis = 0;
        for (int c = 1; c < 3; ++c) {
            if (std::abs(point.position[c]) > std::abs(point.position[axis])) {
                axis = c;
            }
        }
        ASSERT_NEAR(std::abs(point.position[axis]), 0.5f, 1e-5f);
        for (int c = 0; c < 3; ++c) {
            ASSERT_LE(std::abs(point.position[c]), 0.5f + 1e-5f);
            const float expected = c == axis ? std::copysign(1.0f, point.position[axis]) : 0.0f;
            ASSERT_NEAR(point.normal[c], expected, 1e-5f);
            ASSERT_NEAR(point.color[c], srgbByte(kColor[c]), 1);
        }
        ASSERT_EQ(point.color[3], 255);
        ++perFace[axis * 2 + (point.position[axis] > 0.0f)];
    }
    // Equal areas: about 200 each (a binomial's deviation is 13).
    for (int face = 0; face < 6; ++face) {
        EXPECT_GT(perFace[face], 140) << face;
        EXPECT_LT(perFace[face], 260) << face;
    }
    // The seed decides the file.
    const std::string a = readBytes(model / "points.ply");
    EXPECT_EQ(a, readBytes(output / "b" / "cube" / "points.ply"));
    EXPECT_NE(a, readBytes(output / "c" / "cube" / "points.ply"));
    const auto transforms = nlohmann::json::parse(readBytes(model / "transforms.json"));
    EXPECT_EQ(transforms["point_cloud_path"], "./points.ply");
    const auto metadata = nlohmann::json::parse(readBytes(model / "metadata.json"));
    EXPECT_EQ(metadata["pointCloud"]["points"], 1200);
}

TEST(BatchPointCloudTest, BadCountsAreUsageErrors) {
    const fs::path input = writeCube(makeTempDir("point-cloud-bad-input"));
    const fs::path output = makeTempDir("point-cloud-bad-output");
    for (const char* count : {"0", "many", "-3"}) {
        const CommandResult result = runEncore(batchArguments(
            input, output, std::string("--views 1 --size 8 --quiet --point-cloud ") + count));
        EXPECT_EQ(result.exitCode, 2) << count << ": " << result.err;
        EXPECT_NE(result.err.find("--point-cloud"), std::string::npos)
            << count << ": " << result.err;
    }
    EXPECT_TRUE(filesUnder(output, ".ply").empty());
}

}  // namespace
}  // namespace encore::test
