// Every variant of every model in ../shared/models renders with zero WebGPU errors into a
// non-uniform image whose covered area is plausible, and every strategy that shades the same way
// draws exactly the same pixels.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

using test::ModelVariant;

class ModelRenderTest : public ::testing::TestWithParam<ModelVariant> {};

constexpr std::uint32_t kSize = 160;

// Strategies that light an untextured white surface: their images must match exactly, since
// they draw the same triangles with the same shader code and only bind data differently.
constexpr std::array kUnlitStrategies = {StrategyKind::Naive, StrategyKind::Layouts,
                                         StrategyKind::PipelineCache, StrategyKind::Instancing};

TEST_P(ModelRenderTest, EveryStrategyRendersTheSameImageWithoutErrors) {
    const ModelVariant& model = GetParam();
    if (model.path.empty()) {
        GTEST_SKIP() << "../shared/models is absent beside the clone: no sample model rendered";
    }
    ENCORE_REQUIRE_VULKAN(context);
    scene::LoadOptions options;
    options.decodeImages = false;  // These strategies draw no textures.
    auto scene = scene::loadScene(model.path, options);
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    const Camera camera = Camera::framing(scene->bounds, renderer->target().aspect());

    image::ImageRgba8 reference;
    for (StrategyKind kind : kUnlitStrategies) {
        SCOPED_TRACE(strategyName(kind));
        auto prepared = renderer->prepare(*scene, kind);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        const auto frame = renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok()) << image.error().message;
        EXPECT_GT(frame.counters.drawCalls(), 0u);
        if (kind == StrategyKind::Naive) {
            const test::Rgba background = test::pixelAt(*image, 0, 0);
            const double covered = test::coveredFraction(*image, background);
            // Framing fits the bounding sphere, so the model fills a visible part of the view
            // but rarely all of it; an empty image means nothing was drawn.
            EXPECT_GT(covered, 0.002) << model.path;
            EXPECT_LT(covered, 0.98) << model.path;
            reference = std::move(*image);
        } else {
            EXPECT_EQ(test::differingPixels(reference, *image), 0u)
                << strategyName(kind) << " differs from naive on " << model.path;
        }
    }
}

// Strategies that shade with the glTF materials: bundles and GPU culling only change how the
// same draws are recorded and which instances they cover, so with the whole model in view
// their images equal `materials` exactly (blended geometry is sorted the same way in all).
constexpr std::array kMaterialStrategies = {StrategyKind::Materials, StrategyKind::Bundles,
                                            StrategyKind::GpuCulling,
                                            StrategyKind::GpuCullingBundles};

TEST_P(ModelRenderTest, MaterialStrategiesRenderTheSameImageWithoutErrors) {
    const ModelVariant& model = GetParam();
    if (model.path.empty()) {
        GTEST_SKIP() << "../shared/models is absent beside the clone: no sample model rendered";
    }
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadScene(model.path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    // Fully shaded (image-based lighting, every material input) and tone mapped.
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.toneMapping.toneMapping = ToneMapping::PbrNeutral;
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    const Camera camera = Camera::framing(scene->bounds, renderer->target().aspect());

    image::ImageRgba8 reference;
    for (StrategyKind kind : kMaterialStrategies) {
        SCOPED_TRACE(strategyName(kind));
        auto prepared = renderer->prepare(*scene, kind);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok()) << image.error().message;
        if (kind == StrategyKind::Materials) {
            const double covered = test::coveredFraction(*image, test::pixelAt(*image, 0, 0));
            EXPECT_GT(covered, 0.002) << model.path;
            reference = std::move(*image);
        } else {
            EXPECT_EQ(test::differingPixels(reference, *image), 0u)
                << strategyName(kind) << " differs from materials on " << model.path;
        }
    }
}

std::vector<ModelVariant> variants() {
    auto all = test::sharedModelVariants();
    if (all.empty()) {
        // Keeps the suite non-empty; the test itself reports the skip.
        all.push_back({"none", "none", ""});
    }
    return all;
}

INSTANTIATE_TEST_SUITE_P(SharedModels,
                         ModelRenderTest,
                         ::testing::ValuesIn(variants()),
                         [](const auto& info) { return info.param.testName(); });

}  // namespace
}  // namespace encore::render
