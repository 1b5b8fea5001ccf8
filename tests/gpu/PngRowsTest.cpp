// PNG rows filtered on the GPU (batch/PngRowsPass, png_rows.wgsl): the same bytes as the CPU's
// filter from textures of known contents, and `encore batch` writing the same files whichever
// processor filters them.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "BatchOutput.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "batch/PngRowsPass.h"
#include "batch/ViewStrips.h"
#include "encore/batch/Batch.h"
#include "gpu/Readback.h"
#include "gpu/TextureReadbackRing.h"
#include "image/PngWriter.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

wgpu::Texture textureWith(gpu::Context& context,
                          std::uint32_t width,
                          std::uint32_t height,
                          wgpu::TextureFormat format,
                          const void* texels,
                          std::uint32_t bytesPerTexel) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.size = {width, height, 1};
    descriptor.format = format;
    descriptor.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst;
    wgpu::Texture texture = context.device().CreateTexture(&descriptor);
    wgpu::TexelCopyTextureInfo destination{};
    destination.texture = texture;
    wgpu::TexelCopyBufferLayout layout{};
    layout.bytesPerRow = width * bytesPerTexel;
    layout.rowsPerImage = height;
    const wgpu::Extent3D extent{width, height, 1};
    context.queue().WriteTexture(&destination, texels, std::size_t(width) * height * bytesPerTexel,
                                 &layout, &extent);
    return texture;
}

// A half float of `value`, which the test keeps exactly representable (normal or zero).
std::uint16_t exactHalf(float value) {
    if (value == 0.0f) {
        return 0;
    }
    std::uint32_t bits;
    std::memcpy(&bits, &value, 4);
    const std::uint32_t exponent = ((bits >> 23) & 0xff) - 127 + 15;
    return std::uint16_t(((bits >> 16) & 0x8000) | (exponent << 10) | ((bits >> 13) & 0x3ff));
}

// Runs the pass over `source` and returns the mapped read-back.
gpu::MappedReadback readRows(gpu::Context& context,
                             gpu::TextureReadbackRing& ring,
                             PngRowsPass& pass,
                             const wgpu::TextureView& source,
                             const PngRowsLayout& layout,
                             float depthFactor) {
    auto enqueued = ring.enqueueCommands(
        layout.size, [&](const wgpu::CommandEncoder& encoder, const wgpu::Buffer& destination) {
            pass.record(context.queue(), encoder, source, layout, depthFactor, destination);
        });
    EXPECT_TRUE(enqueued.ok()) << enqueued.error().message;
    auto mapped = ring.takeOldestMapped();
    EXPECT_TRUE(mapped.ok()) << mapped.error().message;
    EXPECT_EQ(mapped->size, layout.size);
    return *mapped;
}

// `views` strips of `width` x `height` bytes-per-pixel samples, cut from a wide image.
std::vector<std::uint8_t> stripSamples(const std::vector<std::uint8_t>& wide,
                                       std::uint32_t wideWidth,
                                       std::uint32_t height,
                                       std::uint32_t strip,
                                       std::uint32_t width,
                                       std::size_t bytesPerPixel) {
    std::vector<std::uint8_t> samples;
    for (std::uint32_t y = 0; y < height; ++y) {
        const std::uint8_t* row =
            wide.data() + (std::size_t(y) * wideWidth + std::size_t(strip) * width) * bytesPerPixel;
        samples.insert(samples.end(), row, row + std::size_t(width) * bytesPerPixel);
    }
    return samples;
}

std::vector<std::uint8_t> cpuRows(std::span<const std::uint8_t> samples,
                                  std::uint32_t width,
                                  std::uint32_t height,
                                  std::uint8_t bitDepth,
                                  image::PngColor color,
                                  image::PngCompression compression) {
    std::vector<std::uint8_t> rows(image::filteredPngSize(width, height, bitDepth, color));
    image::filterPngRows(samples, height, image::pngBytesPerPixel(bitDepth, color),
                         image::pngRowFilter(bitDepth, compression), rows.data());
    return rows;
}

// Random bytes with runs and transparent pixels, like a rendered view's.
std::vector<std::uint8_t> viewLikeBytes(std::size_t pixels, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::vector<std::uint8_t> bytes(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i) {
        const bool empty = random() % 3 == 0;
        for (std::size_t c = 0; c < 4; ++c) {
            bytes[i * 4 + c] = empty ? 0 : std::uint8_t(random());
        }
        if (!empty && random() % 2 == 0) {
            bytes[i * 4 + 3] = 255;
        }
    }
    return bytes;
}

TEST(PngRowsTest, ColourRowsAreTheCpuFiltersBytesAndCountCoveredPixels) {
    ENCORE_REQUIRE_VULKAN(context);
    auto pass = PngRowsPass::create(context->device());
    ASSERT_TRUE(pass.ok()) << pass.error().message;
    gpu::TextureReadbackRing ring(*context, 1);
    // Three strips of an odd width: rows that are not whole words.
    constexpr std::uint32_t kWidth = 37;
    constexpr std::uint32_t kHeight = 23;
    constexpr std::uint32_t kViews = 3;
    const std::vector<std::uint8_t> wide = viewLikeBytes(std::size_t(kWidth) * kViews * kHeight, 7);
    const wgpu::Texture texture = textureWith(*context, kWidth * kViews, kHeight,
                                              wgpu::TextureFormat::RGBA8Unorm, wide.data(), 4);
    for (const auto compression : {image::PngCompression::Small, image::PngCompression::Fast}) {
        const PngRowsRequest requests[] = {{ViewImage::Color, PngRowsSource::Bytes},
                                           {ViewImage::Normal, PngRowsSource::LinearBytes}};
        const PngRowsLayout layout = pngRowsLayout(kWidth, kHeight, kViews, requests, compression);
        const gpu::MappedReadback mapped =
            readRows(*context, ring, *pass, texture.CreateView(), layout, 1.0f);
        for (std::uint32_t view = 0; view < kViews; ++view) {
            std::vector<std::uint8_t> samples =
                stripSamples(wide, kWidth * kViews, kHeight, view, kWidth, 4);
            std::uint32_t covered = 0;
            for (std::size_t i = 3; i < samples.size(); i += 4) {
                covered += samples[i] != 0 ? 1 : 0;
            }
            EXPECT_EQ(layout.coveredPixels(mapped.rows, view), covered) << "view " << view;
            const std::vector<std::uint8_t> expected =
                cpuRows(samples, kWidth, kHeight, 8, image::PngColor::Rgba, compression);
            const auto rows = layout.rows(mapped.rows, 0, view);
            ASSERT_EQ(rows.size(), expected.size());
            EXPECT_TRUE(std::equal(rows.begin(), rows.end(), expected.begin()))
                << "colour, view " << view;

            // The normal image: R, G and B through decodeNormalImage's table first.
            image::ImageRgba8 normal{kWidth, kHeight, ReusedBytes(samples.begin(), samples.end())};
            decodeNormalImage(normal);
            const std::vector<std::uint8_t> expectedNormal =
                cpuRows(normal.pixels, kWidth, kHeight, 8, image::PngColor::Rgba, compression);
            const auto normalRows = layout.rows(mapped.rows, 1, view);
            EXPECT_TRUE(std::equal(normalRows.begin(), normalRows.end(), expectedNormal.begin()))
                << "normal, view " << view;
        }
    }
    EXPECT_TRUE(context->checkNoErrors("PNG rows of colour").ok());
}

TEST(PngRowsTest, DepthAndIdRowsAreBigEndianSixteenBitSamples) {
    ENCORE_REQUIRE_VULKAN(context);
    auto pass = PngRowsPass::create(context->device());
    ASSERT_TRUE(pass.ok()) << pass.error().message;
    gpu::TextureReadbackRing ring(*context, 1);
    constexpr std::uint32_t kWidth = 19;
    constexpr std::uint32_t kHeight = 11;
    constexpr std::uint32_t kViews = 2;
    constexpr float kDepthFactor = 1000.0f;
    // Depth x coverage, id % 256 x coverage, id / 256 x coverage, coverage: what the
    // depth-and-id target resolves to, in half floats exactly representable.
    std::vector<std::uint16_t> halves;
    std::vector<std::uint16_t> depths;
    std::vector<std::uint16_t> ids;
    std::mt19937 random(3);
    for (std::uint32_t i = 0; i < kWidth * kViews * kHeight; ++i) {
        const float coverage = std::array{0.0f, 0.25f, 0.5f, 1.0f}[random() % 4];
        const float depth = float(random() % 2048) / 64.0f;  // Steps of 1/64, up to 32.
        const std::uint32_t id = random() % 300;
        const float texel[4] = {depth * coverage, float(id % 256) * coverage,
                                float(id / 256) * coverage, coverage};
        for (const float value : texel) {
            halves.push_back(exactHalf(value));
        }
        const bool covered = coverage >= 0.5f;
        depths.push_back(
            covered ? std::uint16_t(std::clamp(std::lround(depth * kDepthFactor), 1l, 65535l)) : 0);
        ids.push_back(covered ? std::uint16_t(id) : 0);
    }
    const wgpu::Texture texture = textureWith(*context, kWidth * kViews, kHeight,
                                              wgpu::TextureFormat::RGBA16Float, halves.data(), 8);
    const PngRowsRequest requests[] = {{ViewImage::Depth, PngRowsSource::Depth},
                                       {ViewImage::Segmentation, PngRowsSource::Ids}};
    const PngRowsLayout layout =
        pngRowsLayout(kWidth, kHeight, kViews, requests, image::PngCompression::Small);
    EXPECT_FALSE(layout.coverageOffset.has_value());  // Only colour images count pixels.
    const gpu::MappedReadback mapped =
        readRows(*context, ring, *pass, texture.CreateView(), layout, kDepthFactor);
    for (std::size_t image = 0; image < 2; ++image) {
        const std::vector<std::uint16_t>& values = image == 0 ? depths : ids;
        for (std::uint32_t view = 0; view < kViews; ++view) {
            std::vector<std::uint8_t> samples;
            for (std::uint32_t y = 0; y < kHeight; ++y) {
                for (std::uint32_t x = 0; x < kWidth; ++x) {
                    const std::uint16_t value = values[y * kWidth * kViews + view * kWidth + x];
                    samples.push_back(std::uint8_t(value >> 8));
                    samples.push_back(std::uint8_t(value & 0xff));
                }
            }
            // Segmentation is always compressed Fast (runs); both get Up at 16 bits.
            const std::vector<std::uint8_t> expected =
                cpuRows(samples, kWidth, kHeight, 16, image::PngColor::Gray,
                        layout.images[image].compression);
            const auto rows = layout.rows(mapped.rows, image, view);
            ASSERT_EQ(rows.size(), expected.size());
            EXPECT_TRUE(std::equal(rows.begin(), rows.end(), expected.begin()))
                << (image == 0 ? "depth" : "ids") << ", view " << view;
        }
    }
    EXPECT_TRUE(context->checkNoErrors("PNG rows of depth and ids").ok());
}

// More than 65535 workgroups for one view's rows: the grid folds into z.
TEST(PngRowsTest, ViewsOfMoreWorkgroupsThanADimensionHoldAreWrittenWhole) {
    ENCORE_REQUIRE_VULKAN(context);
    auto pass = PngRowsPass::create(context->device());
    ASSERT_TRUE(pass.ok()) << pass.error().message;
    gpu::TextureReadbackRing ring(*context, 1);
    constexpr std::uint32_t kSize = 2048;  // (2048 x 4 + 1) x 2048 bytes: 65,544 workgroups.
    std::vector<std::uint8_t> bytes(std::size_t(kSize) * kSize * 4);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] = std::uint8_t(i * 2654435761u >> 13);
    }
    const wgpu::Texture texture =
        textureWith(*context, kSize, kSize, wgpu::TextureFormat::RGBA8Unorm, bytes.data(), 4);
    const PngRowsRequest request{ViewImage::Albedo, PngRowsSource::Bytes};
    const PngRowsLayout layout =
        pngRowsLayout(kSize, kSize, 1, {&request, 1}, image::PngCompression::Fast);
    const gpu::MappedReadback mapped =
        readRows(*context, ring, *pass, texture.CreateView(), layout, 1.0f);
    const std::vector<std::uint8_t> expected =
        cpuRows(bytes, kSize, kSize, 8, image::PngColor::Rgba, image::PngCompression::Fast);
    const auto rows = layout.rows(mapped.rows, 0, 0);
    ASSERT_EQ(rows.size(), expected.size());
    EXPECT_TRUE(std::memcmp(rows.data(), expected.data(), expected.size()) == 0);
    EXPECT_TRUE(context->checkNoErrors("PNG rows of a large view").ok());
}

TEST(PngRowsTest, AutoFiltersOnTheGpuUnlessTheAdapterIsACpu) {
    EXPECT_TRUE(filtersPngRowsOnGpu(PngFiltering::Auto, wgpu::AdapterType::DiscreteGPU));
    EXPECT_TRUE(filtersPngRowsOnGpu(PngFiltering::Auto, wgpu::AdapterType::IntegratedGPU));
    EXPECT_FALSE(filtersPngRowsOnGpu(PngFiltering::Auto, wgpu::AdapterType::CPU));
    EXPECT_TRUE(filtersPngRowsOnGpu(PngFiltering::Gpu, wgpu::AdapterType::CPU));
    EXPECT_FALSE(filtersPngRowsOnGpu(PngFiltering::Cpu, wgpu::AdapterType::DiscreteGPU));
}

std::vector<BatchInput> passCollection(const fs::path& dir) {
    std::vector<BatchInput> inputs;
    if (const auto models = test::sharedModelsDir()) {
        for (const char* name : {"Duck", "AlphaBlendModeTest", "MetalRoughSpheresNoTextures"}) {
            const fs::path path = *models / name / "glTF-Binary" / (std::string(name) + ".glb");
            if (fs::exists(path)) {
                inputs.push_back({path, name});
            }
        }
    }
    for (std::uint32_t seed = 1; seed <= 2; ++seed) {
        const fs::path path = dir / ("generated" + std::to_string(seed) + ".glb");
        test::writeGeneratedScene(path, 5 + seed, seed);
        inputs.push_back({path, "generated" + std::to_string(seed)});
    }
    return inputs;
}

struct FilteringCase {
    const char* name;
    std::uint32_t samples;
    image::PngCompression compression;
    PassDrawing drawing;
    bool segmentation;
};

void PrintTo(const FilteringCase& filtering, std::ostream* out) {
    *out << filtering.name;
}

class PngRowsBatchTest : public ::testing::TestWithParam<FilteringCase> {};

TEST_P(PngRowsBatchTest, GpuFilteredRowsWriteTheSameFilesAsTheCpu) {
    ENCORE_REQUIRE_VULKAN(context);
    const FilteringCase& filtering = GetParam();
    const fs::path dir = test::makeTempDir(std::string("png-rows-") + filtering.name);
    const std::vector<BatchInput> inputs = passCollection(dir);
    std::map<std::string, std::string> written[2];
    for (const PngFiltering where : {PngFiltering::Cpu, PngFiltering::Gpu}) {
        BatchOptions options;
        options.output = dir / (where == PngFiltering::Gpu ? "gpu" : "cpu");
        options.width = 45;  // Rows of 181 bytes: not whole words.
        options.height = 38;
        options.views.views = 5;
        options.jobs = 2;
        options.samples = filtering.samples;
        options.pngCompression = filtering.compression;
        options.pngFiltering = where;
        options.renderer.environment = test::testEnvironment();
        options.images.normals = true;
        options.images.depth = true;
        options.images.albedo = true;
        options.images.material = true;
        options.images.segmentation = filtering.segmentation;
        options.images.drawing = filtering.drawing;
        auto summary = runBatch(*context, inputs, options);
        ASSERT_TRUE(summary.ok()) << summary.error().message;
        EXPECT_EQ(summary->rendered, inputs.size());
        for (const Failure& failure : summary->failures) {
            ADD_FAILURE() << failure.file << " (" << failure.stage << "): " << failure.error;
        }
        ASSERT_EQ(summary->devices.size(), 1u);
        EXPECT_EQ(summary->devices[0].pngRowsOnGpu, where == PngFiltering::Gpu);
        written[where == PngFiltering::Gpu ? 1 : 0] = test::batchOutputFiles(options.output);
    }
    // Per model: five views of colour and four or five passes, metadata.json, transforms.json.
    const std::size_t images = filtering.segmentation ? 6 : 5;
    EXPECT_EQ(written[0].size(), inputs.size() * (5 * images + 2));
    ASSERT_EQ(written[1].size(), written[0].size());
    for (const auto& [name, bytes] : written[0]) {
        const auto found = written[1].find(name);
        ASSERT_NE(found, written[1].end()) << name << " is missing when the GPU filters";
        EXPECT_TRUE(found->second == bytes) << name << " differs when the GPU filters";
    }
    EXPECT_TRUE(context->checkNoErrors("the batches").ok());
}

INSTANTIATE_TEST_SUITE_P(
    Filterings,
    PngRowsBatchTest,
    ::testing::Values(
        FilteringCase{"targets_small", 1, image::PngCompression::Small, PassDrawing::Targets, true},
        FilteringCase{"targets_fast", 1, image::PngCompression::Fast, PassDrawing::Targets, true},
        FilteringCase{"targets_4x", 4, image::PngCompression::Small, PassDrawing::Targets, false},
        FilteringCase{"frames", 1, image::PngCompression::Small, PassDrawing::Frames, true}),
    [](const ::testing::TestParamInfo<FilteringCase>& info) { return info.param.name; });

}  // namespace
}  // namespace encore::batch
