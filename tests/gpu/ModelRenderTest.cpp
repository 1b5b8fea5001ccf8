// Every variant of every model in ../shared/models renders with zero WebGPU errors into a
// non-uniform image whose covered area is plausible.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "TestPaths.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

using test::ModelVariant;

class ModelRenderTest : public ::testing::TestWithParam<ModelVariant> {};

constexpr std::uint32_t kSize = 160;

TEST_P(ModelRenderTest, RendersWithoutErrors) {
    const ModelVariant& model = GetParam();
    if (model.path.empty()) {
        GTEST_SKIP() << "../shared/models is absent beside the clone: no sample model rendered";
    }
    ENCORE_REQUIRE_VULKAN(context);
    scene::LoadOptions options;
    options.decodeImages = false;  // The naive strategy draws no textures.
    auto scene = scene::loadScene(model.path, options);
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    auto renderer = Renderer::create(*context, {{kSize, kSize, 1}});
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    auto prepared = renderer->prepare(*scene, StrategyKind::Naive);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    const auto frame =
        renderer->renderFrame(Camera::framing(scene->bounds, renderer->target().aspect()));
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_GT(frame.counters.drawCalls(), 0u);

    const test::Rgba background = test::pixelAt(*image, 0, 0);
    const double covered = test::coveredFraction(*image, background);
    // Framing fits the bounding sphere, so the model fills a visible part of the view but
    // rarely all of it; an empty image means nothing was drawn.
    EXPECT_GT(covered, 0.002) << model.path;
    EXPECT_LT(covered, 0.98) << model.path;
}

std::vector<ModelVariant> variants() {
    auto all = test::sharedModelVariants();
    if (all.empty()) {
        // Keeps the suite non-empty; the test itself reports the skip.
        all.push_back({"none", "none", "", });
    }
    return all;
}

INSTANTIATE_TEST_SUITE_P(SharedModels, ModelRenderTest, ::testing::ValuesIn(variants()),
                         [](const auto& info) { return info.param.testName(); });

}  // namespace
}  // namespace encore::render
