// The visibility strategy in `encore batch` (docs/visibility.md, "In batches"): a renderer that
// prepares model after model (RendererOptions::keepPipelines) creates the strategy's pipelines
// and target-sized buffers once and draws the same pictures with them, and a batch with
// `--strategy visibility` writes what the default strategy writes, within the SSIM bound,
// at one sample and at four.

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "BatchOutput.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestFiles.h"
#include "TestPaths.h"
#include "VisibilityTestSupport.h"
#include "encore/batch/Batch.h"
#include "encore/render/Renderer.h"
#include "gpu/CreationCounts.h"
#include "gpu/Readback.h"
#include "gpu/ResourcePool.h"
#include "image/ImageDecoders.h"
#include "render/renderer/RendererCore.h"
#include "render/visibility/VisibilityFeatures.h"
#include "render/visibility/VisibilityPipelines.h"
#include "render/visibility/VisibilityStrategy.h"
#include "render/visibility/VisibilityTarget.h"

namespace encore::render {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kViewSize = 64;
constexpr std::size_t kViews = 3;

// `encore gen --objects 24 --meshes 4 --tessellation N`: dense models, textured materials.
scene::GeneratorOptions denseModel(std::uint32_t seed, std::uint32_t tessellation) {
    scene::GeneratorOptions options;
    options.objectCount = 24;
    options.meshCount = 4;
    options.tessellation = tessellation;
    options.seed = seed;
    options.textures = true;
    return options;
}

// Three views around the scene, side by side in one frame (as a batch's strip).
std::vector<Camera> stripCameras(const scene::SceneData& scene) {
    const glm::vec3 center = scene.bounds.center();
    const float distance = 1.6f * glm::length(scene.bounds.max - scene.bounds.min);
    std::vector<Camera> cameras;
    for (std::size_t view = 0; view < kViews; ++view) {
        const float angle = 2.1f * float(view);
        const glm::vec3 eye = center + distance * glm::vec3(std::cos(angle), 0.5f, std::sin(angle));
        cameras.push_back(Camera::lookAt(eye, center, glm::radians(45.0f), 1.0f, 0.05f * distance,
                                         4.0f * distance));
    }
    return cameras;
}

image::ImageRgba8 renderStrip(Renderer& renderer, const scene::SceneData& scene) {
    const std::vector<Camera> cameras = stripCameras(scene);
    renderer.renderViews(cameras);
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

RendererOptions stripOptions(std::uint32_t samples, bool keep) {
    RendererOptions options = test::pixelTestOptions(kViewSize * kViews, kViewSize, samples);
    options.keepPipelines = keep;
    return options;
}

// The second model of a batch creates none of the visibility strategy's pipelines again, reuses
// the target's buffers, and draws, at both sample counts, pixel for pixel what a renderer that
// prepared only that model draws.
TEST(VisibilityBatchTest, KeptPipelinesAreCreatedOnceAndDrawTheSamePictures) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData first = test::generatedScene(denseModel(1, 12));
    const scene::SceneData second = test::generatedScene(denseModel(2, 12));
    for (const std::uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE(testing::Message() << samples << " samples");
        auto keeping = Renderer::create(*context, stripOptions(samples, true));
        ASSERT_TRUE(keeping.ok()) << keeping.error().message;
        ASSERT_TRUE(keeping->prepare(first, StrategyKind::Visibility).ok());
        EXPECT_EQ(internals(*keeping).setup().pipelinesCreated,
                  VisibilityPipelines::createdPipelines(samples, true));
        renderStrip(*keeping, first);
        const auto* strategy =
            dynamic_cast<const VisibilityStrategy*>(internals(*keeping).strategy());
        ASSERT_NE(strategy, nullptr);
        const WGPUTexture firstPyramid = strategy->depthPyramid().texture().Get();

        auto prepared = keeping->prepare(second, StrategyKind::Visibility);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        EXPECT_EQ(internals(*keeping).setup().pipelinesCreated, 0u);
        const image::ImageRgba8 kept = renderStrip(*keeping, second);
        strategy = dynamic_cast<const VisibilityStrategy*>(internals(*keeping).strategy());
        ASSERT_NE(strategy, nullptr);
        EXPECT_EQ(strategy->depthPyramid().texture().Get(), firstPyramid)
            << "the target's resources were made again";
        EXPECT_EQ(strategy->lastViewCount(), kViews);

        // Without keeping (the default), each prepare creates the strategy's pipelines (the
        // shading ones on first use).
        auto plain = Renderer::create(*context, stripOptions(samples, false));
        ASSERT_TRUE(plain.ok()) << plain.error().message;
        ASSERT_TRUE(plain->prepare(second, StrategyKind::Visibility).ok());
        EXPECT_EQ(internals(*plain).setup().pipelinesCreated,
                  VisibilityPipelines::createdPipelines(samples, false));
        const image::ImageRgba8 fresh = renderStrip(*plain, second);
        EXPECT_EQ(test::differingPixels(kept, fresh), 0u);
        EXPECT_GT(test::coveredFraction(fresh, test::pixelAt(fresh, 0, 0)), 0.05);

        // A resized target makes the target's resources again, and the bind groups over them.
        ASSERT_TRUE(keeping->resize(kViewSize * kViews, kViewSize / 2).ok());
        ASSERT_TRUE(plain->resize(kViewSize * kViews, kViewSize / 2).ok());
        EXPECT_EQ(test::differingPixels(renderStrip(*keeping, second), renderStrip(*plain, second)),
                  0u);
    }
    EXPECT_TRUE(context->checkNoErrors("kept visibility pipelines").ok());
}

// In a batch the scene-sized buffers come from the lane's pool: a model drawn again after
// another creates no GPU object, and draws what it drew the first time.
TEST(VisibilityBatchTest, PooledSceneBuffersAreReusedAndDrawTheSamePictures) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData first = test::generatedScene(denseModel(1, 12));
    const scene::SceneData second = test::generatedScene(denseModel(2, 12));
    gpu::ResourcePool pool(context->device());  // Outlives the renderer's scenes.
    auto renderer = Renderer::create(*context, stripOptions(4, true));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    internals(*renderer).setResourcePool(&pool);
    ASSERT_TRUE(renderer->prepare(first, StrategyKind::Visibility).ok());
    const image::ImageRgba8 drawnFirst = renderStrip(*renderer, first);
    ASSERT_TRUE(renderer->prepare(second, StrategyKind::Visibility).ok());
    renderStrip(*renderer, second);

    const gpu::CreationCounts before = gpu::threadCreationCounts();
    const std::uint64_t reused = pool.reused();
    auto prepared = renderer->prepare(first, StrategyKind::Visibility);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    renderer->renderViews(stripCameras(first));
    EXPECT_EQ((gpu::threadCreationCounts() - before).objects(), 0u);  // Not the test's read.
    const image::ImageRgba8 drawnAgain = renderStrip(*renderer, first);
    EXPECT_GE(pool.reused() - reused, 7u);  // The strategy's seven, besides the scene's.
    EXPECT_EQ(test::differingPixels(drawnAgain, drawnFirst), 0u);
    EXPECT_GT(test::coveredFraction(drawnAgain, test::pixelAt(drawnAgain, 0, 0)), 0.05);
    EXPECT_TRUE(context->checkNoErrors("visibility in pooled buffers").ok());
}

// The kept working buffers (units, triangle lists, bins) grow with the largest model so far and
// serve every smaller one after it: what a larger model left in them changes no pixel of a
// smaller one's picture.
TEST(VisibilityBatchTest, KeptWorkBuffersGrowForLargerModelsOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData small = test::generatedScene(denseModel(1, 4));
    const scene::SceneData large = test::generatedScene(denseModel(2, 16));
    auto keeping = Renderer::create(*context, stripOptions(1, true));
    ASSERT_TRUE(keeping.ok()) << keeping.error().message;
    auto plain = Renderer::create(*context, stripOptions(1, false));
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    auto kept = [&] {
        return dynamic_cast<const VisibilityStrategy*>(internals(*keeping).strategy());
    };
    // Its bytes (handles of a buffer released and one made after it can be equal).
    auto workgroupListBytes = [&] { return kept()->workBuffers().workgroupList.GetSize(); };
    // At least 8 per triangle (a block each).
    auto neededBytes = [&] { return std::uint64_t(kept()->tables().triangleCount) * 8; };

    ASSERT_TRUE(keeping->prepare(small, StrategyKind::Visibility).ok());
    ASSERT_NE(kept(), nullptr);
    renderStrip(*keeping, small);
    const std::uint64_t smallBytes = workgroupListBytes();
    ASSERT_TRUE(keeping->prepare(large, StrategyKind::Visibility).ok());
    const image::ImageRgba8 largeKept = renderStrip(*keeping, large);
    const std::uint64_t largeBytes = workgroupListBytes();
    EXPECT_GT(largeBytes, smallBytes) << "the larger model needs larger buffers";
    EXPECT_GE(largeBytes, neededBytes());

    ASSERT_TRUE(keeping->prepare(small, StrategyKind::Visibility).ok());
    const image::ImageRgba8 smallKept = renderStrip(*keeping, small);
    EXPECT_EQ(workgroupListBytes(), largeBytes) << "a smaller model makes none again";
    EXPECT_GT(workgroupListBytes(), neededBytes());

    ASSERT_TRUE(plain->prepare(small, StrategyKind::Visibility).ok());
    const image::ImageRgba8 smallFresh = renderStrip(*plain, small);
    EXPECT_GT(test::coveredFraction(smallFresh, test::pixelAt(smallFresh, 0, 0)), 0.05);
    EXPECT_EQ(test::differingPixels(smallKept, smallFresh), 0u);
    ASSERT_TRUE(plain->prepare(large, StrategyKind::Visibility).ok());
    EXPECT_EQ(test::differingPixels(largeKept, renderStrip(*plain, large)), 0u);
    EXPECT_TRUE(context->checkNoErrors("kept visibility work buffers").ok());
}

// The hardware raster draws one view of a strip at a time into a depth attachment of one view's
// size, its fragments shifted back to the view's place: with every triangle sent to the hardware
// (no compute raster), each view of the strip is pixel for pixel what the compute raster draws.
TEST(VisibilityBatchTest, HardwareRasterisedViewsLandInTheirPlaceInTheStrip) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = test::generatedScene(denseModel(4, 6));
    for (const std::uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE(testing::Message() << samples << " samples");
        RendererOptions hardwareOnly = stripOptions(samples, false);
        hardwareOnly.culling.computeRasterPixels = 0.0f;
        hardwareOnly.culling.workgroupRasterPixels = 0.0f;
        auto hardware = Renderer::create(*context, hardwareOnly);
        ASSERT_TRUE(hardware.ok()) << hardware.error().message;
        ASSERT_TRUE(hardware->prepare(scene, StrategyKind::Visibility).ok());
        const image::ImageRgba8 drawn = renderStrip(*hardware, scene);
        const auto* strategy =
            dynamic_cast<const VisibilityStrategy*>(internals(*hardware).strategy());
        ASSERT_NE(strategy, nullptr);
        ASSERT_EQ(strategy->rasterCountsOffset(1), 8u) << "a copy per view, side by side";
        auto counts = gpu::readBuffer(*context, strategy->rasterCounts(), 0, kViews * 8);
        ASSERT_TRUE(counts.ok()) << counts.error().message;
        for (std::size_t view = 0; view < kViews; ++view) {
            std::uint32_t inCompute = 0;
            std::uint32_t inHardware = 0;
            std::memcpy(&inCompute, counts->data() + view * 8, 4);
            std::memcpy(&inHardware, counts->data() + view * 8 + 4, 4);
            EXPECT_EQ(inCompute, 0u) << "view " << view;
            EXPECT_GT(inHardware, 0u) << "view " << view;
        }

        auto mixed = Renderer::create(*context, stripOptions(samples, false));
        ASSERT_TRUE(mixed.ok()) << mixed.error().message;
        ASSERT_TRUE(mixed->prepare(scene, StrategyKind::Visibility).ok());
        const image::ImageRgba8 reference = renderStrip(*mixed, scene);
        EXPECT_GT(test::coveredFraction(reference, test::pixelAt(reference, 0, 0)), 0.05);
        EXPECT_EQ(test::differingPixels(drawn, reference), 0u);
    }
    EXPECT_TRUE(context->checkNoErrors("hardware-rasterised strips").ok());
}

// Triangles listed whole (here: past a block list cut to three entries, with every triangle
// over a pixel across sent to the workgroup raster) are clipped and covered by workgroups view
// by view of a strip, each in its view's place: pixel for pixel the strip drawn with room for
// every block, at one sample and at four.
TEST(VisibilityBatchTest, TrianglesListedWholeLandInTheirPlaceInTheStrip) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = test::generatedScene(denseModel(5, 6));
    for (const std::uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE(testing::Message() << samples << " samples");
        RendererOptions options = stripOptions(samples, false);
        options.culling.computeRasterPixels = 1.0f;
        auto roomy = Renderer::create(*context, options);
        ASSERT_TRUE(roomy.ok()) << roomy.error().message;
        ASSERT_TRUE(roomy->prepare(scene, StrategyKind::Visibility).ok());
        const image::ImageRgba8 reference = renderStrip(*roomy, scene);
        EXPECT_GT(test::coveredFraction(reference, test::pixelAt(reference, 0, 0)), 0.05);

        auto full = Renderer::create(*context, options);
        ASSERT_TRUE(full.ok()) << full.error().message;
        ASSERT_TRUE(full->prepare(scene, StrategyKind::Visibility).ok());
        // The renderer hands its strategy out const; this shrinks a list of it.
        auto* strategy = const_cast<VisibilityStrategy*>(
            dynamic_cast<const VisibilityStrategy*>(internals(*full).strategy()));
        ASSERT_NE(strategy, nullptr);
        strategy->limitWorkgroupBlocks(3);
        EXPECT_EQ(test::differingPixels(renderStrip(*full, scene), reference), 0u);
        auto counts = gpu::readBuffer(*context, strategy->rasterCounts(), 0, kViews * 8);
        ASSERT_TRUE(counts.ok()) << counts.error().message;
        for (std::size_t view = 0; view < kViews; ++view) {
            std::uint32_t inHardware = 1;
            std::memcpy(&inHardware, counts->data() + view * 8 + 4, 4);
            EXPECT_EQ(inHardware, 0u) << "view " << view;
        }
        // The last view's list of triangles listed whole: three vertices per entry
        // (visibility_counters.wgsl's hardwareVertices, at byte 16).
        EXPECT_GT(test::readWord(*context, strategy->counters(), 16), 3u);
    }
    EXPECT_TRUE(context->checkNoErrors("strips past a full block list").ok());
}

// A renderer that makes its own pipelines makes the shading ones on first use, for the bin kinds
// and the view mode its frames draw: frames of one view read their parameters from their
// bindings, frames of several views copy them from their view's slot. Both draw what the kept
// slots' pipelines draw.
TEST(VisibilityBatchTest, ShadingPipelinesAreMadeForWhatFramesDraw) {
    ENCORE_REQUIRE_VULKAN(context);
    constexpr std::uint64_t kOthers = VisibilityPipelines::createdPipelines(1, false);
    const scene::SceneData scene = test::generatedScene(denseModel(1, 12));
    auto plain = Renderer::create(*context, stripOptions(1, false));
    auto kept = Renderer::create(*context, stripOptions(1, true));
    ASSERT_TRUE(plain.ok() && kept.ok());
    ASSERT_TRUE(plain->prepare(scene, StrategyKind::Visibility).ok());
    EXPECT_EQ(internals(*plain).setup().pipelinesCreated, kOthers);
    ASSERT_TRUE(kept->prepare(scene, StrategyKind::Visibility).ok());

    const Camera camera = stripCameras(scene)[0];
    plain->renderFrame(camera);
    const std::uint64_t oneView = internals(*plain).setup().pipelinesCreated;
    EXPECT_GT(oneView, kOthers);
    EXPECT_LT(oneView, VisibilityPipelines::createdPipelines(1, true))
        << "only the scene's bin kinds";
    auto drawn = plain->readImage();
    kept->renderFrame(camera);
    auto keptDrawn = kept->readImage();
    ASSERT_TRUE(drawn.ok() && keptDrawn.ok());
    EXPECT_EQ(test::differingPixels(*drawn, *keptDrawn), 0u);
    EXPECT_GT(test::coveredFraction(*drawn, test::pixelAt(*drawn, 0, 0)), 0.05);
    plain->renderFrame(camera);
    EXPECT_EQ(internals(*plain).setup().pipelinesCreated, oneView);

    const image::ImageRgba8 strip = renderStrip(*plain, scene);
    EXPECT_EQ(internals(*plain).setup().pipelinesCreated, oneView + (oneView - kOthers));
    EXPECT_EQ(test::differingPixels(strip, renderStrip(*kept, scene)), 0u);
    EXPECT_TRUE(context->checkNoErrors("shading pipelines on first use").ok());
}

// encore batch creates the kept pipelines while its loaders read the first models: the first
// prepare then compiles none of the strategy's own, and draws what a fresh renderer draws.
TEST(VisibilityBatchTest, KeptObjectsCreatedAheadSpareTheFirstPrepare) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = test::generatedScene(denseModel(1, 12));
    auto ahead = Renderer::create(*context, stripOptions(1, true));
    ASSERT_TRUE(ahead.ok()) << ahead.error().message;
    ASSERT_TRUE(ahead->createKeptObjects(StrategyKind::Bundles).ok());
    EXPECT_EQ(internals(*ahead).setup().pipelinesCreated, 0u) << "other strategies keep nothing";
    ASSERT_TRUE(ahead->createKeptObjects(StrategyKind::Visibility).ok());
    EXPECT_EQ(internals(*ahead).setup().pipelinesCreated,
              VisibilityPipelines::createdPipelines(1, true));
    ASSERT_TRUE(ahead->createKeptObjects(StrategyKind::Visibility).ok());  // Once.
    EXPECT_EQ(internals(*ahead).setup().pipelinesCreated,
              VisibilityPipelines::createdPipelines(1, true));
    ASSERT_TRUE(ahead->prepare(scene, StrategyKind::Visibility).ok());
    EXPECT_LT(internals(*ahead).setup().pipelinesCreated,
              VisibilityPipelines::createdPipelines(1, true));
    const image::ImageRgba8 drawn = renderStrip(*ahead, scene);

    auto plain = Renderer::create(*context, stripOptions(1, false));
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    ASSERT_TRUE(plain->prepare(scene, StrategyKind::Visibility).ok());
    EXPECT_EQ(test::differingPixels(drawn, renderStrip(*plain, scene)), 0u);
    EXPECT_TRUE(context->checkNoErrors("kept objects created ahead").ok());
}

// Binning and shading take up to VisibilityTarget::kSlotViews views at once; a frame of more
// does them in groups. Each view of a frame of 260 (two groups) is pixel for pixel the same view
// in a frame of 130 (one group).
TEST(VisibilityBatchTest, FramesOfMoreViewsThanASlotBindingShadeInGroups) {
    ENCORE_REQUIRE_VULKAN(context);
    constexpr std::size_t kManyViews = 260;
    static_assert(kManyViews > VisibilityTarget::kSlotViews);
    constexpr std::uint32_t kWidth = 4;
    constexpr std::uint32_t kHeight = 8;
    const scene::SceneData scene = test::generatedScene(denseModel(3, 8));
    const glm::vec3 center = scene.bounds.center();
    const float distance = 0.9f * glm::length(scene.bounds.max - scene.bounds.min);
    std::vector<Camera> cameras;
    for (std::size_t view = 0; view < kManyViews; ++view) {
        const float angle = 0.05f * float(view);
        const glm::vec3 eye = center + distance * glm::vec3(std::cos(angle), 0.4f, std::sin(angle));
        cameras.push_back(Camera::lookAt(eye, center, glm::radians(20.0f), float(kWidth) / kHeight,
                                         0.05f * distance, 4.0f * distance));
    }
    auto render = [&](std::span<const Camera> views) {
        auto renderer = Renderer::create(
            *context, test::pixelTestOptions(kWidth * std::uint32_t(views.size()), kHeight));
        EXPECT_TRUE(renderer.ok());
        EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
        renderer->renderViews(views);
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok());
        return std::move(*image);
    };
    const image::ImageRgba8 all = render(cameras);
    const std::size_t half = kManyViews / 2;
    const image::ImageRgba8 first = render(std::span(cameras).first(half));
    const image::ImageRgba8 second = render(std::span(cameras).subspan(half));
    std::size_t differing = 0;
    std::size_t covered = 0;
    const test::Rgba background = test::pixelAt(first, 0, 0) == test::pixelAt(second, 0, 0)
                                      ? test::pixelAt(first, 0, 0)
                                      : test::Rgba{};
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < all.width; ++x) {
            const std::uint32_t halfWidth = kWidth * std::uint32_t(half);
            const test::Rgba expected = x < halfWidth ? test::pixelAt(first, x, y)
                                                      : test::pixelAt(second, x - halfWidth, y);
            differing += test::pixelAt(all, x, y) != expected;
            covered += x >= kWidth * VisibilityTarget::kSlotViews && expected != background;
        }
    }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(covered, 0u) << "the second group's views show nothing";
    EXPECT_TRUE(context->checkNoErrors("views in groups").ok());
}

// The kept objects belong to the device: a renderer rebuilt after a device loss makes them again
// on the new one and draws the same strip.
TEST(VisibilityBatchTest, KeptObjectsAreMadeAgainAfterADeviceLoss) {
    ENCORE_REQUIRE_VULKAN(shared);
    gpu::ContextOptions contextOptions;
    requestVisibilityFeatures(contextOptions);
    // An own context: losing the process-wide one would take the other tests with it.
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok()) << context.error().message;
    const scene::SceneData scene = test::generatedScene(denseModel(4, 8));
    RendererOptions options = stripOptions(4, true);
    options.environment = nullptr;  // The shared test environment lives on another device.
    options.environmentOptions = test::testEnvironmentOptions();
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
    const image::ImageRgba8 before = renderStrip(*renderer, scene);

    context->device().ForceLoss(wgpu::DeviceLostReason::Unknown, "lost on purpose by a test");
    for (int attempt = 0; attempt < 200 && !context->deviceLost(); ++attempt) {
        context->instance().ProcessEvents();
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(context->deviceLost());
    auto recovered = renderer->recoverFromDeviceLoss();
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_GE(internals(*renderer).setup().pipelinesCreated,
              VisibilityPipelines::createdPipelines(4, true));
    EXPECT_EQ(test::differingPixels(renderStrip(*renderer, scene), before), 0u);
    EXPECT_TRUE(context->checkNoErrors("visibility after a device loss").ok());
}

// Writes a generated dense model as `path`.
void writeDenseModel(const fs::path& path, std::uint32_t seed) {
    auto glb = scene::generateSceneGlb(denseModel(seed, 24));
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb->data()), std::streamsize(glb->size()));
}

std::map<std::string, std::string> runStrategy(gpu::Context& context,
                                               const std::vector<batch::BatchInput>& inputs,
                                               const fs::path& output,
                                               std::uint32_t samples,
                                               std::optional<StrategyChoice> strategy) {
    batch::BatchOptions options;
    options.output = output;
    options.width = 80;
    options.height = 80;
    options.views.views = 4;
    options.samples = samples;
    options.jobs = 2;
    options.renderers = 1;  // Every model after the first on a renderer that drew one before.
    options.strategy = strategy;
    options.renderer.environment = test::testEnvironment();
    auto summary = batch::runBatch(context, inputs, options);
    EXPECT_TRUE(summary.ok()) << summary.error().message;
    if (summary.ok()) {
        EXPECT_EQ(summary->rendered, inputs.size());
        for (const batch::Failure& failure : summary->failures) {
            ADD_FAILURE() << failure.file << " (" << failure.stage << "): " << failure.error;
        }
    }
    return test::batchOutputFiles(output);
}

image::ImageRgba8 decoded(const std::string& bytes) {
    auto image = image::decodePng(
        std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
    EXPECT_TRUE(image.ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// `encore batch --strategy visibility` on dense generated models: every view within SSIM 0.98
// of the default strategy's (issue 28's batch bound), at four samples (the default) and one.
TEST(VisibilityBatchTest, StripsLookLikeTheDefaultStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    const fs::path dir = test::makeTempDir("visibility-batch");
    std::vector<batch::BatchInput> inputs;
    for (std::uint32_t seed = 1; seed <= 2; ++seed) {
        const fs::path path = dir / ("dense" + std::to_string(seed) + ".glb");
        writeDenseModel(path, seed);
        inputs.push_back({path, "dense" + std::to_string(seed)});
    }
    for (const std::uint32_t samples : {4u, 1u}) {
        SCOPED_TRACE(testing::Message() << samples << " samples");
        const std::string suffix = std::to_string(samples);
        const auto expected =
            runStrategy(*context, inputs, dir / ("default" + suffix), samples, std::nullopt);
        const auto drawn = runStrategy(*context, inputs, dir / ("visibility" + suffix), samples,
                                       StrategyChoice::of(StrategyKind::Visibility, false));
        std::size_t compared = 0;
        for (const auto& [name, bytes] : expected) {
            if (name.size() < 4 || name.substr(name.size() - 4) != ".png") {
                continue;
            }
            SCOPED_TRACE(name);
            const auto found = drawn.find(name);
            ASSERT_NE(found, drawn.end());
            const image::ImageRgba8 reference = decoded(bytes);
            const image::ImageRgba8 image = decoded(found->second);
            EXPECT_GT(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.05);
            test::expectVisibilityClose(reference, image, 0.02, 0.98);
            ++compared;
        }
        EXPECT_EQ(compared, inputs.size() * 4);
    }
    EXPECT_TRUE(context->checkNoErrors("visibility batches").ok());
}

}  // namespace
}  // namespace encore::render
