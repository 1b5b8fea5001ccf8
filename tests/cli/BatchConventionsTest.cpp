// encore batch's pass conventions (issue 50, docs/batch.md#conventions): depth along the axis or
// the ray, in normalised or model units; normals in world or camera axes, shading or geometric,
// in 8 or 16 bits or EXR; object coordinates. Checked on a square facing the first camera whose
// values are known.

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <spng.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
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

// A square from -1 to 1 in x and y at z = 0 (normalised to half that: 0.5 normalised units per
// model unit), its vertex normals all `vertexNormal`, so that the shading normal is
// `vertexNormal` and the triangles' own is +Z; `unlit`: KHR_materials_unlit.
fs::path writeSquare(const fs::path& dir, glm::vec3 vertexNormal, bool unlit = false) {
    GltfBuilder builder;
    const auto positions = builder.addPositions(
        {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {-1.0f, 1.0f, 0.0f}});
    const auto normals =
        builder.addNormals(std::vector<glm::vec3>(4, glm::normalize(vertexNormal)));
    const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    const auto material = builder.addMaterial({.baseColor = glm::vec4(0.8f), .roughness = 0.5f});
    const auto mesh =
        builder.addMesh({{{.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                           .indices = indices,
                           .material = material}}},
                        "square");
    builder.addScene({builder.addNode({.mesh = mesh, .name = "square"})});
    if (unlit) {
        builder.json()["materials"][0]["extensions"]["KHR_materials_unlit"] =
            nlohmann::json::object();
        builder.json()["extensionsUsed"] = {"KHR_materials_unlit"};
    }
    fs::create_directories(dir);
    return builder.writeGlb(dir, "square");
}

// One channel of an EXR file as floats.
std::vector<float> readExrChannel(const fs::path& path, const char* channel) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    EXPECT_NE(file.header().channels().findChannel(channel), nullptr) << channel;
    std::vector<float> values(std::size_t(width) * height);
    Imf::FrameBuffer frame;
    frame.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()),
                                     sizeof(float), sizeof(float) * width));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return values;
}

// A PNG's samples in its own bit depth (8 or 16, host byte order), and its header.
std::vector<std::uint16_t> readPngSamples(const fs::path& path, spng_ihdr& header) {
    const std::string bytes = readBytes(path);
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> context(spng_ctx_new(0), spng_ctx_free);
    spng_set_png_buffer(context.get(), bytes.data(), bytes.size());
    EXPECT_EQ(spng_get_ihdr(context.get(), &header), 0);
    std::size_t size = 0;
    spng_decoded_image_size(context.get(), SPNG_FMT_PNG, &size);
    std::vector<std::uint8_t> raw(size);
    EXPECT_EQ(spng_decode_image(context.get(), raw.data(), size, SPNG_FMT_PNG, 0), 0);
    std::vector<std::uint16_t> samples;
    if (header.bit_depth == 16) {
        samples.resize(raw.size() / 2);
        std::memcpy(samples.data(), raw.data(), raw.size());
    } else {
        samples.assign(raw.begin(), raw.end());
    }
    return samples;
}

nlohmann::json readTransforms(const fs::path& model) {
    return nlohmann::json::parse(readBytes(model / "transforms.json"));
}

constexpr std::uint32_t kSize = 32;
// 0.6 from the square's centre with a 60-degree view: the square (1 x 1 normalised) covers the
// whole image, so that its corners are off the axis.
const std::string kClose =
    "--views 1 --elevation 0 --size 32 --samples 1 --distance 0.6 "
    "--fov 60 --quiet ";

TEST(BatchConventionsTest, RayDepthIsAxisDepthOverTheCosineOfTheRaysAngle) {
    const fs::path input = writeSquare(makeTempDir("conventions-depth-input"), {0, 0, 1});
    const fs::path output = makeTempDir("conventions-depth-output");
    for (const char* kind : {"z", "ray"}) {
        const CommandResult run = runEncore(batchArguments(
            input, output / kind, kClose + "--depth --depth-format exr --depth-kind " + kind));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    }
    const std::vector<float> z = readExrChannel(output / "z/square/000_depth.exr", "Z");
    const std::vector<float> ray = readExrChannel(output / "ray/square/000_depth.exr", "Z");
    ASSERT_EQ(z.size(), std::size_t(kSize) * kSize);
    const auto transforms = readTransforms(output / "ray/square");
    EXPECT_EQ(transforms["depth_kind"], "ray");
    EXPECT_EQ(transforms["depth_unit"], "normalized");
    EXPECT_FALSE(readTransforms(output / "z/square").contains("depth_kind"));
    const double focal = transforms["fl_x"];
    const double cx = transforms["cx"];
    const double cy = transforms["cy"];
    // Every pixel sees the plane 0.6 ahead; its ray is longer by 1 / cos of its angle.
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const std::size_t i = std::size_t(y) * kSize + x;
            ASSERT_NEAR(z[i], 0.6f, 1e-3f) << x << ", " << y;
            const double dx = (x + 0.5 - cx) / focal;
            const double dy = (y + 0.5 - cy) / focal;
            ASSERT_NEAR(ray[i] / z[i], std::sqrt(1.0 + dx * dx + dy * dy), 1e-3) << x << ", " << y;
        }
    }
    // At a corner the rays are a quarter longer (60 degrees across 32 pixels).
    EXPECT_GT(ray[0] / z[0], 1.25f);
    EXPECT_NEAR(ray[0], ray[kSize * kSize - 1], 1e-3f);
}

TEST(BatchConventionsTest, ModelUnitsUndoTheNormalisation) {
    const fs::path input = writeSquare(makeTempDir("conventions-unit-input"), {0, 0, 1});
    const fs::path output = makeTempDir("conventions-unit-output");
    for (const char* unit : {"normalized", "model"}) {
        for (const char* format : {"exr", "png"}) {
            const CommandResult run = runEncore(batchArguments(
                input, output / (std::string(unit) + "-" + format),
                kClose + "--depth --depth-format " + format + " --depth-unit " + unit));
            ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
        }
    }
    // The square's side of 2 model units is 1 normalised unit: 0.6 normalised is 1.2 metres.
    const std::size_t centre = (kSize / 2) * kSize + kSize / 2;
    EXPECT_NEAR(readExrChannel(output / "normalized-exr/square/000_depth.exr", "Z")[centre], 0.6f,
                1e-3f);
    EXPECT_NEAR(readExrChannel(output / "model-exr/square/000_depth.exr", "Z")[centre], 1.2f,
                2e-3f);
    // A PNG keeps its steps; its depth_scale says what they are in metres.
    spng_ihdr header{};
    const auto normalized = readPngSamples(output / "normalized-png/square/000_depth.png", header);
    ASSERT_EQ(header.bit_depth, 16);
    const auto model = readPngSamples(output / "model-png/square/000_depth.png", header);
    EXPECT_EQ(normalized, model);
    const double normalizedScale = readTransforms(output / "normalized-png/square")["depth_scale"];
    const auto modelTransforms = readTransforms(output / "model-png/square");
    const double modelScale = modelTransforms["depth_scale"];
    EXPECT_NEAR(modelScale, 2.0 * normalizedScale, 1e-9);
    EXPECT_NEAR(model[centre] * modelScale, 1.2, 2e-3);
    EXPECT_EQ(modelTransforms["depth_unit"], "model");
    const auto metadata =
        nlohmann::json::parse(readBytes(output / "model-png/square/metadata.json"));
    EXPECT_EQ(metadata["passes"]["depth"],
              nlohmann::json::parse(R"({"kind": "z", "unit": "model", "format": "png"})"));
}

// A camera-space normal (PNG: n * 0.5 + 0.5) at the image's centre.
glm::dvec3 centreNormal(const fs::path& path) {
    spng_ihdr header{};
    const auto samples = readPngSamples(path, header);
    EXPECT_EQ(header.color_type, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA);
    const double top = header.bit_depth == 16 ? 65535.0 : 255.0;
    const std::size_t texel = ((header.height / 2) * header.width + header.width / 2) * 4;
    EXPECT_EQ(samples[texel + 3], top);  // Covered.
    return glm::dvec3(samples[texel], samples[texel + 1], samples[texel + 2]) / top * 2.0 - 1.0;
}

TEST(BatchConventionsTest, CameraSpaceNormalsFollowTheCameraConvention) {
    const fs::path input = writeSquare(makeTempDir("conventions-normal-input"), {0, 0, 1});
    const fs::path output = makeTempDir("conventions-normal-output");
    // Facing the camera: +Z toward it in OpenGL's and Blender's camera axes, -Z in OpenCV's.
    const std::vector<std::pair<std::string, glm::dvec3>> facing = {
        {"opengl", {0, 0, 1}}, {"blender", {0, 0, 1}}, {"opencv", {0, 0, -1}}};
    for (const auto& [convention, expected] : facing) {
        const fs::path out = output / convention;
        const CommandResult run =
            runEncore(batchArguments(input, out,
                                     kClose +
                                         "--normals --normal-space camera --normal-format png16 "
                                         "--camera-convention " +
                                         convention));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
        const glm::dvec3 n = centreNormal(out / "square/000_normal.png");
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(n[c], expected[c], 2e-3) << convention << " axis " << c;
        }
        EXPECT_EQ(readTransforms(out / "square")["normal_space"], "camera");
    }
    // From 30 degrees above, the camera's own axes (transforms.json's matrix, in the convention)
    // take the world's +Z to (0, -0.5, 0.87) in OpenGL's: R^T n.
    for (const char* convention : {"opengl", "opencv"}) {
        const fs::path out = output / (std::string("above-") + convention);
        const CommandResult run = runEncore(batchArguments(
            input, out,
            std::string("--views 1 --elevation 30 --size 32 --samples 1 --quiet --normals "
                        "--normal-space camera --normal-format png16 --camera-convention ") +
                convention));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
        const auto matrix = readTransforms(out / "square")["frames"][0]["transform_matrix"];
        glm::dvec3 expected;
        for (int axis = 0; axis < 3; ++axis) {
            expected[axis] = matrix[2][axis];  // Row z of column `axis`: the axis dotted with +Z.
        }
        const glm::dvec3 n = centreNormal(out / "square/000_normal.png");
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(n[c], expected[c], 2e-3) << convention << " axis " << c;
        }
        EXPECT_NEAR(std::abs(expected.y), 0.5, 1e-3) << convention;
    }
}

TEST(BatchConventionsTest, GeometricNormalsIgnoreTheVertexNormals) {
    // Vertex normals leaning toward +X: the shading normal leans, the triangles' does not.
    const fs::path input = writeSquare(makeTempDir("conventions-geometric-input"), {0.6, 0, 0.8});
    const fs::path output = makeTempDir("conventions-geometric-output");
    for (const char* kind : {"shading", "geometric"}) {
        const CommandResult run = runEncore(batchArguments(
            input, output / kind,
            kClose + "--normals --normal-format exr --normal-kind " + std::string(kind)));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    }
    const std::size_t centre = (kSize / 2) * kSize + kSize / 2;
    const fs::path shading = output / "shading/square/000_normal.exr";
    const fs::path geometric = output / "geometric/square/000_normal.exr";
    EXPECT_NEAR(readExrChannel(shading, "R")[centre], 0.6f, 2e-3f);
    EXPECT_NEAR(readExrChannel(shading, "B")[centre], 0.8f, 2e-3f);
    EXPECT_NEAR(readExrChannel(geometric, "R")[centre], 0.0f, 2e-3f);
    EXPECT_NEAR(readExrChannel(geometric, "G")[centre], 0.0f, 2e-3f);
    EXPECT_NEAR(readExrChannel(geometric, "B")[centre], 1.0f, 2e-3f);
    EXPECT_EQ(readExrChannel(geometric, "A")[centre], 1.0f);
    const auto transforms = readTransforms(output / "geometric/square");
    EXPECT_EQ(transforms["normal_kind"], "geometric");
    EXPECT_EQ(transforms["normal_format"], "exr");
    EXPECT_EQ(transforms["frames"][0]["normal_file_path"], "./000_normal");
    EXPECT_FALSE(fs::exists(output / "geometric/square/000_normal.png"));

    // An unlit surface has a geometry too.
    const fs::path unlit =
        writeSquare(makeTempDir("conventions-geometric-unlit-input"), {0.6, 0, 0.8}, true);
    const CommandResult run = runEncore(batchArguments(
        unlit, output / "unlit", kClose + "--normals --normal-format exr --normal-kind geometric"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    const fs::path unlitNormal = output / "unlit/square/000_normal.exr";
    EXPECT_NEAR(readExrChannel(unlitNormal, "R")[centre], 0.0f, 2e-3f);
    EXPECT_NEAR(readExrChannel(unlitNormal, "B")[centre], 1.0f, 2e-3f);
}

TEST(BatchConventionsTest, ObjectCoordinatesAreThePositionsInTheNormalisedBox) {
    const fs::path input = writeSquare(makeTempDir("conventions-coordinates-input"), {0, 0, 1});
    const fs::path output = makeTempDir("conventions-coordinates-output");
    for (const char* format : {"png16", "exr"}) {
        const CommandResult run = runEncore(batchArguments(
            input, output / format, kClose + "--coordinates --coordinates-format " + format));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    }
    spng_ihdr header{};
    const auto png = readPngSamples(output / "png16/square/000_coordinates.png", header);
    ASSERT_EQ(header.bit_depth, 16);
    ASSERT_EQ(header.color_type, SPNG_COLOR_TYPE_TRUECOLOR_ALPHA);
    const fs::path exr = output / "exr/square/000_coordinates.exr";
    const std::vector<float> channels[] = {readExrChannel(exr, "R"), readExrChannel(exr, "G"),
                                           readExrChannel(exr, "B"), readExrChannel(exr, "A")};
    const auto transforms = readTransforms(output / "png16/square");
    EXPECT_EQ(transforms["coordinates_format"], "png16");
    EXPECT_EQ(transforms["frames"][0]["coordinates_file_path"], "./000_coordinates");
    const double focal = transforms["fl_x"];
    const double cx = transforms["cx"];
    const double cy = transforms["cy"];
    // The square (side 2, at z = 0) fills the box's x and y from 0 to 1 and sits at z = 0.5; the
    // camera 0.6 in front of its centre sees (0.6 dx, -0.6 dy) through pixel (x, y).
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const std::size_t i = std::size_t(y) * kSize + x;
            const double expected[] = {0.5 + 0.6 * (x + 0.5 - cx) / focal,
                                       0.5 - 0.6 * (y + 0.5 - cy) / focal, 0.5, 1.0};
            for (int c = 0; c < 4; ++c) {
                ASSERT_NEAR(channels[c][i], expected[c], 2e-3)
                    << x << ", " << y << " channel " << c;
                ASSERT_NEAR(png[i * 4 + c] / 65535.0, expected[c], 2e-3)
                    << x << ", " << y << " channel " << c;
            }
        }
    }

    // An unlit surface has its coordinates too (not its colour).
    const fs::path unlit =
        writeSquare(makeTempDir("conventions-coordinates-unlit-input"), {0, 0, 1}, true);
    const CommandResult run =
        runEncore(batchArguments(unlit, output / "unlit", kClose + "--coordinates"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    const auto unlitPng = readPngSamples(output / "unlit/square/000_coordinates.png", header);
    const std::size_t centre = ((kSize / 2) * kSize + kSize / 2) * 4;
    EXPECT_NEAR(unlitPng[centre] / 65535.0, 0.5 + 0.6 * 0.5 / focal, 2e-3);
    EXPECT_NEAR(unlitPng[centre + 1] / 65535.0, 0.5 - 0.6 * 0.5 / focal, 2e-3);
    EXPECT_NEAR(unlitPng[centre + 2] / 65535.0, 0.5, 2e-3);
}

TEST(BatchConventionsTest, BadConventionsAreUsageErrors) {
    const fs::path input = writeSquare(makeTempDir("conventions-bad-input"), {0, 0, 1});
    const fs::path output = makeTempDir("conventions-bad-output");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--depth-kind ray", "--depth-kind requires --depth"},
        {"--depth --depth-kind far", "--depth-kind takes z or ray (not 'far')"},
        {"--depth-unit model", "--depth-unit requires --depth"},
        {"--depth --depth-unit cm", "--depth-unit takes normalized or model"},
        {"--normal-space camera", "--normal-space requires --normals"},
        {"--normals --normal-space tangent", "--normal-space takes world or camera"},
        {"--normals --normal-kind smooth", "--normal-kind takes shading or geometric"},
        {"--normal-format exr", "--normal-format requires --normals"},
        {"--normals --normal-format tiff", "--normal-format takes png8, png16 or exr"},
        {"--coordinates-format exr", "--coordinates-format requires --coordinates"},
        {"--coordinates --coordinates-format png8", "--coordinates-format takes png16 or exr"},
        {"--coordinates -s naive", "need a strategy that draws glTF materials"},
        {"--normals --normal-kind geometric -s naive", "geometric normals need a strategy"},
    };
    expectUsageErrors(input, output, "--views 1 --size 8 --quiet ", cases);
}

}  // namespace
}  // namespace encore::test
