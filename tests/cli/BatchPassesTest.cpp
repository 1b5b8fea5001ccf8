// encore batch's passes (issue 29): albedo, material, segmentation, EXR depth and HDR images
// beside each view, checked on a model whose values are known: two quads side by side facing
// the first camera, at the orbit's centre, each its own node, mesh and material.

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <half.h>
#include <spng.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "BatchCommandSupport.h"
#include "BatchOutput.h"
#include "CommandRunner.h"
#include "GeneratedModels.h"
#include "GltfBuilder.h"
#include "TestPaths.h"
#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

struct QuadDesc {
    const char* name;
    float left;
    float right;
    glm::vec4 color;
    float metallic;
    float roughness;
};

// Quads at z = 0, x from -1 to -0.2 and 0.2 to 1, y from -0.5 to 0.5: normalised (largest side
// 2) to half that, 1.5 in front of view 0 of an orbit at elevation 0.
constexpr QuadDesc kLeft{"left quad", -1.0f, -0.2f, {0.8f, 0.2f, 0.1f, 1.0f}, 0.0f, 0.6f};
constexpr QuadDesc kRight{"right quad", 0.2f, 1.0f, {1.0f, 1.0f, 1.0f, 1.0f}, 0.25f, 0.4f};

fs::path writeQuads(const fs::path& dir) {
    GltfBuilder builder;
    std::vector<std::uint32_t> nodes;
    for (const QuadDesc& quad : {kLeft, kRight}) {
        const auto positions = builder.addPositions({{quad.left, -0.5f, 0.0f},
                                                     {quad.right, -0.5f, 0.0f},
                                                     {quad.right, 0.5f, 0.0f},
                                                     {quad.left, 0.5f, 0.0f}});
        const auto normals = builder.addNormals(std::vector<glm::vec3>(4, {0.0f, 0.0f, 1.0f}));
        const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        const auto material = builder.addMaterial(
            {.baseColor = quad.color, .metallic = quad.metallic, .roughness = quad.roughness});
        const auto mesh =
            builder.addMesh({{{.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                               .indices = indices,
                               .material = material}}},
                            std::string(quad.name) + " mesh");
        nodes.push_back(builder.addNode({.mesh = mesh, .name = quad.name}));
    }
    builder.addScene(nodes);
    fs::create_directories(dir);
    return builder.writeGlb(dir, "quads");
}

// A 16-bit greyscale PNG's values.
std::vector<std::uint16_t> readGray16(const fs::path& path, std::uint32_t& width) {
    const std::string bytes = readBytes(path);
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> context(spng_ctx_new(0), spng_ctx_free);
    spng_set_png_buffer(context.get(), bytes.data(), bytes.size());
    spng_ihdr header{};
    EXPECT_EQ(spng_get_ihdr(context.get(), &header), 0);
    EXPECT_EQ(header.bit_depth, 16);
    EXPECT_EQ(header.color_type, SPNG_COLOR_TYPE_GRAYSCALE);
    std::size_t size = 0;
    spng_decoded_image_size(context.get(), SPNG_FMT_PNG, &size);
    std::vector<std::uint8_t> raw(size);
    EXPECT_EQ(spng_decode_image(context.get(), raw.data(), size, SPNG_FMT_PNG, 0), 0);
    width = header.width;
    std::vector<std::uint16_t> values(raw.size() / 2);
    std::memcpy(values.data(), raw.data(), raw.size());  // SPNG_FMT_PNG: host byte order.
    return values;
}

// One channel of an EXR file, as floats, read through OpenEXR.
std::vector<float> readExrChannel(const fs::path& path, const char* channel, int& width) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    width = window.max.x - window.min.x + 1;
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

std::uint8_t srgbByte(float linear) {
    const double encoded =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return std::uint8_t(std::lround(encoded * 255.0));
}

const std::string kView = "--views 1 --elevation 0 --size 64 --samples 1 --quiet ";
// Pixels inside the left and right quads and in the gap between them (64 x 64, 1.5 away).
constexpr std::uint32_t kLeftX = 18, kRightX = 46, kGapX = 32, kRow = 32;

TEST(BatchPassesTest, EveryPassHoldsTheKnownValuesOfTwoQuads) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-input"));
    const fs::path output = makeTempDir("batch-passes-output");
    const CommandResult run = runEncore(batchArguments(
        input, output,
        kView + "--normals --depth --depth-format exr --albedo --material --segmentation --hdr"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    const fs::path model = output / "quads";

    auto color = image::readImage(model / "000.png");
    auto albedo = image::readImage(model / "000_albedo.png");
    auto material = image::readImage(model / "000_material.png");
    auto normal = image::readImage(model / "000_normal.png");
    ASSERT_TRUE(color.ok() && albedo.ok() && material.ok() && normal.ok());
    ASSERT_EQ(albedo->width, 64u);
    // The colour image's alpha, pixel for pixel, in every 8-bit pass.
    for (std::size_t i = 3; i < color->pixels.size(); i += 4) {
        ASSERT_EQ(albedo->pixels[i], color->pixels[i]) << "albedo alpha at byte " << i;
        ASSERT_EQ(material->pixels[i], color->pixels[i]) << "material alpha at byte " << i;
        ASSERT_EQ(normal->pixels[i], color->pixels[i]) << "normal alpha at byte " << i;
    }
    EXPECT_EQ(color->pixel(kGapX, kRow)[3], 0);
    for (const auto& [x, quad] : {std::pair{kLeftX, kLeft}, std::pair{kRightX, kRight}}) {
        ASSERT_EQ(color->pixel(x, kRow)[3], 255) << quad.name;
        for (int c = 0; c < 3; ++c) {
            // Albedo: the factor, sRGB-encoded.
            EXPECT_NEAR(albedo->pixel(x, kRow)[c], srgbByte(quad.color[c]), 1) << quad.name << c;
        }
        // Material: occlusion 1 (no texture), roughness, metallic, linear.
        EXPECT_NEAR(material->pixel(x, kRow)[0], 255, 1) << quad.name;
        EXPECT_NEAR(material->pixel(x, kRow)[1], quad.roughness * 255.0f, 1) << quad.name;
        EXPECT_NEAR(material->pixel(x, kRow)[2], quad.metallic * 255.0f, 1) << quad.name;
        // Normal +Z: (0.5, 0.5, 1) stored.
        EXPECT_NEAR(normal->pixel(x, kRow)[2], 255, 2) << quad.name;
        EXPECT_NEAR(normal->pixel(x, kRow)[0], 128, 2) << quad.name;
    }

    // Segmentation: 1 + the node index, 0 in the gap; the names in transforms.json.
    std::uint32_t width = 0;
    const std::vector<std::uint16_t> ids = readGray16(model / "000_segmentation.png", width);
    ASSERT_EQ(width, 64u);
    EXPECT_EQ(ids[kRow * 64 + kLeftX], 1);
    EXPECT_EQ(ids[kRow * 64 + kRightX], 2);
    EXPECT_EQ(ids[kRow * 64 + kGapX], 0);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        ASSERT_EQ(ids[i] != 0, color->pixels[i * 4 + 3] == 255) << "pixel " << i;
    }
    const auto transforms = nlohmann::json::parse(readBytes(model / "transforms.json"));
    EXPECT_EQ(transforms["segmentation_by"], "node");
    EXPECT_EQ(transforms["segmentation_ids"],
              nlohmann::json::parse(R"([{"id": 1, "name": "left quad"},
                                        {"id": 2, "name": "right quad"}])"));
    const auto& frame = transforms["frames"][0];
    EXPECT_EQ(frame["albedo_file_path"], "./000_albedo");
    EXPECT_EQ(frame["material_file_path"], "./000_material");
    EXPECT_EQ(frame["segmentation_file_path"], "./000_segmentation");
    EXPECT_EQ(frame["hdr_file_path"], "./000_hdr");
    EXPECT_EQ(frame["depth_file_path"], "./000_depth");
    EXPECT_EQ(transforms["depth_format"], "exr");
    EXPECT_FALSE(transforms.contains("depth_scale"));

    // EXR depth: 1.5 along the camera axis on both quads, infinity in the gap.
    int exrWidth = 0;
    const std::vector<float> depth = readExrChannel(model / "000_depth.exr", "Z", exrWidth);
    ASSERT_EQ(exrWidth, 64);
    EXPECT_NEAR(depth[kRow * 64 + kLeftX], 1.5f, 1e-4f);
    EXPECT_NEAR(depth[kRow * 64 + kRightX], 1.5f, 1e-4f);
    EXPECT_TRUE(std::isinf(depth[kRow * 64 + kGapX]) && depth[kRow * 64 + kGapX] > 0.0f);
    EXPECT_TRUE(std::isinf(depth[0]));

    // HDR: linear radiance, alpha the coverage.
    const std::vector<float> alpha = readExrChannel(model / "000_hdr.exr", "A", exrWidth);
    EXPECT_EQ(alpha[kRow * 64 + kLeftX], 1.0f);
    EXPECT_EQ(alpha[kRow * 64 + kGapX], 0.0f);
    EXPECT_FALSE(fs::exists(model / "000_depth.png"));
}

// With 4 samples the edges are partly covered: the 8-bit passes keep the colour image's alpha
// there too.
TEST(BatchPassesTest, MultisampledPassesKeepTheColourAlpha) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-msaa-input"));
    const fs::path output = makeTempDir("batch-passes-msaa-output");
    const CommandResult run = runEncore(batchArguments(
        input, output,
        "--views 1 --elevation 20 --size 64 --samples 4 --quiet --albedo --material --normals"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    auto color = image::readImage(output / "quads/000.png");
    ASSERT_TRUE(color.ok());
    std::size_t partial = 0;
    for (const char* pass : {"albedo", "material", "normal"}) {
        auto image = image::readImage(output / "quads" / ("000_" + std::string(pass) + ".png"));
        ASSERT_TRUE(image.ok()) << pass;
        for (std::size_t i = 3; i < color->pixels.size(); i += 4) {
            ASSERT_EQ(image->pixels[i], color->pixels[i]) << pass << " alpha at byte " << i;
            partial += color->pixels[i] != 0 && color->pixels[i] != 255;
        }
    }
    EXPECT_GT(partial, 0u) << "no partly covered edge pixel was compared";
}

// With the segmentation counting meshes or materials, the ids follow them (the nodes' order is
// the same here) and transforms.json names them.
TEST(BatchPassesTest, SegmentationByMeshAndMaterialNamesThem) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-by-input"));
    const fs::path output = makeTempDir("batch-passes-by-output");
    for (const char* by : {"mesh", "material"}) {
        const CommandResult run = runEncore(
            batchArguments(input, output / by, kView + "--segmentation --segmentation-by " + by));
        ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
        std::uint32_t width = 0;
        const auto ids = readGray16(output / by / "quads/000_segmentation.png", width);
        EXPECT_EQ(ids[kRow * 64 + kLeftX], 1) << by;
        EXPECT_EQ(ids[kRow * 64 + kRightX], 2) << by;
        const auto transforms =
            nlohmann::json::parse(readBytes(output / by / "quads/transforms.json"));
        EXPECT_EQ(transforms["segmentation_by"], by);
        ASSERT_EQ(transforms["segmentation_ids"].size(), 2u) << by;
        if (std::string(by) == "mesh") {
            EXPECT_EQ(transforms["segmentation_ids"][1]["name"], "right quad mesh");
        }
    }
}

// Where the tone-mapped PNG saturates, the HDR image holds the radiance beyond 1.
TEST(BatchPassesTest, HdrHoldsRadianceWhereThePngSaturates) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-hdr-input"));
    const fs::path output = makeTempDir("batch-passes-hdr-output");
    const CommandResult run = runEncore(
        batchArguments(input, output, kView + "--hdr --tonemap none --environment-intensity 6"));
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    auto color = image::readImage(output / "quads/000.png");
    ASSERT_TRUE(color.ok());
    int width = 0;
    const std::vector<float> green = readExrChannel(output / "quads/000_hdr.exr", "G", width);
    ASSERT_EQ(color->pixel(kRightX, kRow)[1], 255) << "the white quad saturates";
    EXPECT_GT(green[kRow * 64 + kRightX], 1.0f);
}

// The same options write the same bytes, EXR files included.
TEST(BatchPassesTest, SameSeedWritesIdenticalPasses) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-same-input"));
    const fs::path output = makeTempDir("batch-passes-same-output");
    const std::string passes =
        "--random-views 2 --seed 5 --size 32 --samples 1 --quiet --normals "
        "--depth --depth-format exr --albedo --material --segmentation "
        "--hdr";
    for (const char* run : {"a", "b"}) {
        const CommandResult result = runEncore(batchArguments(input, output / run, passes));
        ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    const auto a = batchOutputFiles(output / "a");
    EXPECT_EQ(a.size(), 2u * 7 + 2);  // Seven images per view, metadata and transforms.
    EXPECT_TRUE(a == batchOutputFiles(output / "b")) << "the same seed wrote other bytes";
}

// The passes drawn in the colour frame's render pass (the default) write the bytes that one
// frame per pass writes (--pass-frames): the shader computes the same values for both, and
// blending and the resolve treat them alike. Three views in one target, 1 and 4 samples, and
// some of the shared models (a blended, a textured and a normal-mapped one) where present.
TEST(BatchPassesTest, PassTargetsWriteTheBytesOfOneFramePerPass) {
    const fs::path input = makeTempDir("batch-pass-targets-input");
    writeQuads(input);
    if (const auto models = sharedModelsDir()) {
        for (const char* name : {"AlphaBlendModeTest", "BoxTextured", "NormalTangentTest"}) {
            const fs::path model = *models / name / "glTF-Binary" / (std::string(name) + ".glb");
            if (fs::exists(model)) {
                fs::copy_file(model, input / model.filename());
            }
        }
    }
    const fs::path output = makeTempDir("batch-pass-targets-output");
    const std::string views = "--views 3 --size 40 --quiet --normals --depth --albedo --material ";
    const std::pair<const char*, std::string> runs[] = {
        {"one sample", views + "--samples 1 --segmentation --depth-format exr --hdr"},
        {"four samples", views + "--samples 4 --segmentation"},
    };
    for (const auto& [label, options] : runs) {
        SCOPED_TRACE(label);
        for (const char* drawing : {"targets", "frames"}) {
            const bool frames = drawing == std::string("frames");
            const CommandResult run = runEncore(batchArguments(
                input, output / label / drawing, options + (frames ? " --pass-frames" : "")));
            ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
            // Each drawing as asked for (the device line of -v says which).
            EXPECT_EQ(run.out.find("passes drawn in the colour pass") != std::string::npos, !frames)
                << run.out;
        }
        const auto targets = batchOutputFiles(output / label / "targets");
        const auto frames = batchOutputFiles(output / label / "frames");
        EXPECT_GE(targets.size(), 3u * 5 + 2);
        ASSERT_EQ(targets.size(), frames.size());
        for (const auto& [file, bytes] : targets) {
            ASSERT_TRUE(frames.count(file)) << file;
            EXPECT_TRUE(bytes == frames.at(file)) << file << " differs between the two drawings";
        }
    }
}

// The cut square (GeneratedModels.h) as cut.glb in `dir`.
fs::path writeCutSquare(const fs::path& dir) {
    fs::create_directories(dir);
    const std::vector<std::uint8_t> glb = cutSquareGlb(1.0f, 0.4f);
    std::ofstream(dir / "cut.glb", std::ios::binary)
        .write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    return dir / "cut.glb";
}

// Issue 50: at 4 samples (the default) the ids stay exact while the colour is antialiased: every
// pixel holds an id that was drawn (one sample's), never the average of the two pieces' ids
// along the cut; the ids at 1 sample differ only at edges; both drawings write the same ids.
TEST(BatchPassesTest, SegmentationAtFourSamplesHoldsDrawnIds) {
    const fs::path input = writeCutSquare(makeTempDir("batch-exact-ids-input"));
    const fs::path output = makeTempDir("batch-exact-ids-output");
    const std::string view = "--views 1 --elevation 0 --size 64 --quiet --segmentation ";
    for (const char* run : {"one", "targets", "frames"}) {
        const std::string samples = run == std::string("one") ? "--samples 1" : "--samples 4";
        const std::string frames = run == std::string("frames") ? " --pass-frames" : "";
        const CommandResult result =
            runEncore(batchArguments(input, output / run, view + samples + frames));
        ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    }
    std::uint32_t width = 0;
    const auto one = readGray16(output / "one/cut/000_segmentation.png", width);
    const auto four = readGray16(output / "targets/cut/000_segmentation.png", width);
    ASSERT_EQ(width, 64u);
    ASSERT_EQ(one.size(), 64u * 64u);
    ASSERT_EQ(four.size(), one.size());
    EXPECT_TRUE(four == readGray16(output / "frames/cut/000_segmentation.png", width))
        << "--pass-frames wrote other ids";
    std::size_t cut = 0;
    for (std::uint32_t y = 0; y < 64; ++y) {
        for (std::uint32_t x = 0; x < 64; ++x) {
            const std::uint16_t id = four[y * 64 + x];
            ASSERT_TRUE(id == 0 || id == 1 || id == 4) << id << " at " << x << "," << y;
            // The ids at 1 sample within one pixel.
            std::set<std::uint16_t> around;
            for (std::uint32_t ny = y ? y - 1 : 0; ny <= std::min(y + 1, 63u); ++ny) {
                for (std::uint32_t nx = x ? x - 1 : 0; nx <= std::min(x + 1, 63u); ++nx) {
                    around.insert(one[ny * 64 + nx]);
                }
            }
            cut += around.count(1) && around.count(4);
            if (id != one[y * 64 + x]) {
                EXPECT_GT(around.size(), 1u) << "not an edge pixel: " << x << "," << y;
            }
        }
    }
    EXPECT_GT(cut, 32u) << "the cut between ids 1 and 4 crosses the image";
    // The colour is antialiased at 4 samples: partly covered edge pixels.
    auto color = image::readImage(output / "targets/cut/000.png");
    ASSERT_TRUE(color.ok());
    std::size_t partial = 0;
    for (std::size_t i = 3; i < color->pixels.size(); i += 4) {
        partial += color->pixels[i] != 0 && color->pixels[i] != 255;
    }
    EXPECT_GT(partial, 32u);
}

TEST(BatchPassesTest, BadCombinationsAreUsageErrors) {
    const fs::path input = writeQuads(makeTempDir("batch-passes-bad-input"));
    const fs::path output = makeTempDir("batch-passes-bad-output");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--depth-format exr", "--depth-format requires --depth"},
        {"--depth --depth-format tiff", "--depth-format"},
        {"--segmentation-by mesh --samples 1", "--segmentation-by requires --segmentation"},
        {"--segmentation --samples 1 --segmentation-by scene", "--segmentation-by"},
        {"--segmentation --samples 1 -s visibility", "not visibility"},
        {"--albedo -s naive", "need a strategy that draws glTF materials"},
    };
    expectUsageErrors(input, output, "--views 1 --size 8 --quiet ", cases);
}

// Issue 50's camera options: a bad preset, list or pose file is a usage error (exit 2) that names
// the option or file and the problem, before anything renders.
TEST(BatchPassesTest, BadCamerasAreUsageErrors) {
    const fs::path input = writeQuads(makeTempDir("batch-cameras-bad-input"));
    const fs::path output = makeTempDir("batch-cameras-bad-output");
    const fs::path dir = makeTempDir("batch-cameras-bad-poses");
    std::ofstream(dir / "broken.json") << "{\"frames\": [";
    std::ofstream(dir / "sheared.json") << "[[[1,1,0,0],[0,1,0,0],[0,0,1,2],[0,0,0,1]]]";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--preset zero124", "--preset takes zero123, zero123plus"},
        {"--azimuths 0,x", "--azimuths takes numbers separated by commas"},
        {"--azimuths 0,90 --elevations 1,2,3", "lists differ in length (2 and 3)"},
        {"--elevations 100", "elevations must lie in [-90, 90] (not 100)"},
        {"--ortho-scale 2", "--ortho-scale requires --projection"},
        {"--poses " + (dir / "missing.json").string(), "--poses '"},
        {"--poses " + (dir / "broken.json").string(), "broken.json': not valid JSON"},
        {"--poses " + (dir / "sheared.json").string(),
         "sheared.json': camera 0: the matrix is not a rigid camera pose"},
        {"--camera-convention directx", "--camera-convention"},
    };
    expectUsageErrors(input, output, "--size 8 --quiet ", cases);
}

}  // namespace
}  // namespace encore::test
