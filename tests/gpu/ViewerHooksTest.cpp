// What the interactive viewer needs from the renderer: resizing the target without recording
// bundles again, any strategy drawn from a render bundle (the bundling axis), and GPU culling
// against a frozen frustum while the camera moves elsewhere.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

scene::SceneData generatedScene() {
    scene::GeneratorOptions generator;
    generator.objectCount = 60;
    generator.meshCount = 4;
    generator.materialCount = 3;
    return test::generatedScene(generator);
}

RendererOptions options(std::uint32_t width, std::uint32_t height) {
    RendererOptions result = test::pixelTestOptions(width, height);
    result.target.sampleCount = 4;  // Resizing re-creates the multisampled textures too.
    return result;
}

image::ImageRgba8 render(const scene::SceneData& scene,
                         StrategyKind kind,
                         bool bundle,
                         std::uint32_t width,
                         std::uint32_t height) {
    gpu::Context* context = test::vulkanContext();
    auto renderer = Renderer::create(*context, options(width, height));
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(scene, kind, bundle).ok());
    renderer->renderFrame(Camera::framing(scene.bounds, float(width) / float(height)));
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return std::move(*image);
}

struct Case {
    StrategyKind kind;
    bool bundle;
};

TEST(ViewerHooksTest, ResizingKeepsTheRecordedBundlesAndRendersLikeANewTarget) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    for (const Case& c :
         {Case{StrategyKind::Bundles, false}, Case{StrategyKind::GpuCullingBundles, false},
          Case{StrategyKind::Naive, true}, Case{StrategyKind::Instancing, true}}) {
        SCOPED_TRACE(std::string(strategyName(c.kind)) + (c.bundle ? " bundled" : ""));
        auto renderer = Renderer::create(*context, options(64, 48));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, c.kind, c.bundle).ok());
        renderer->renderFrame(Camera::framing(scene.bounds, 64.0f / 48.0f));
        ASSERT_TRUE(renderer->readImage().ok());
        const std::uint64_t recorded = internals(*renderer).strategy()->report().bundlesRecorded;
        EXPECT_GE(recorded, 1u);

        ASSERT_TRUE(renderer->resize(96, 80).ok());
        EXPECT_EQ(renderer->target().width(), 96u);
        EXPECT_EQ(renderer->target().height(), 80u);
        const FrameResult frame = renderer->renderFrame(Camera::framing(scene.bounds, 1.2f));
        auto resized = renderer->readImage();
        ASSERT_TRUE(resized.ok()) << resized.error().message;
        EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, recorded);
        EXPECT_EQ(frame.counters.executeBundles, test::bundlesPerRecording(c.kind));
        const image::ImageRgba8 fresh = render(scene, c.kind, c.bundle, 96, 80);
        ASSERT_EQ(resized->width, fresh.width);
        ASSERT_EQ(resized->height, fresh.height);
        EXPECT_EQ(test::differingPixels(*resized, fresh), 0u);
        EXPECT_GT(test::coveredFraction(*resized, test::pixelAt(*resized, 0, 0)), 0.02);
    }
}

// With an environment background, drawn in the frame's render pass: with a plain colour the
// visibility strategy composes its frame in compute and records no render pass to replay
// (FramePasses::composesFrame), while its bundled form still draws the composite from a bundle.
TEST(ViewerHooksTest, EveryStrategyCanDrawItsFrameFromABundle) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    RendererOptions withEnvironment = options(64, 64);
    withEnvironment.toneMapping.background = BackgroundKind::Environment;
    for (StrategyKind kind : allStrategies()) {
        SCOPED_TRACE(strategyName(kind));
        auto direct = Renderer::create(*context, withEnvironment);
        auto bundled = Renderer::create(*context, withEnvironment);
        ASSERT_TRUE(direct.ok() && bundled.ok());
        // A bundled kind (bundles, gpu-culling-bundles) is compared with its direct kind.
        ASSERT_TRUE(direct->prepare(scene, directKind(kind).value_or(kind)).ok());
        ASSERT_TRUE(bundled->prepare(scene, kind, true).ok());
        EXPECT_TRUE(bundled->bundled());
        EXPECT_EQ(internals(*bundled).strategy()->kind(), bundledKind(kind).value_or(kind));
        const FrameResult directFrame = direct->renderFrame(camera);
        FrameResult bundledFrame;
        for (int frame = 0; frame < 3; ++frame) {
            bundledFrame = bundled->renderFrame(camera);
        }
        auto directImage = direct->readImage();
        auto bundledImage = bundled->readImage();
        ASSERT_TRUE(directImage.ok() && bundledImage.ok());
        EXPECT_EQ(test::differingPixels(*directImage, *bundledImage), 0u);
        EXPECT_EQ(bundledFrame.counters.drawCalls(), 0u);
        const StrategyKind recordedKind = internals(*bundled).strategy()->kind();
        EXPECT_EQ(bundledFrame.counters.executeBundles, test::bundlesPerRecording(recordedKind));
        EXPECT_EQ(internals(*bundled).strategy()->report().bundlesRecorded,
                  test::bundlesPerRecording(recordedKind));
        EXPECT_EQ(bundledFrame.bundleContents.drawCalls(), directFrame.counters.drawCalls());
    }
}

TEST(ViewerHooksTest, AFrozenCullingFrustumCullsWhatItDoesNotSee) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = generatedScene();
    auto renderer = Renderer::create(*context, options(64, 64));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::GpuCullingBundles).ok());
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    // A frustum looking away from the scene: everything is culled while the camera sees it all.
    const glm::vec3 center = 0.5f * (scene.bounds.min + scene.bounds.max);
    const glm::vec3 away = camera.position + (camera.position - center);
    renderer->setCullingCamera(
        Camera::lookAt(camera.position, away, glm::radians(45.0f), 1.0f, 0.01f, 0.0f));
    renderer->renderFrame(camera);
    auto culled = renderer->readImage();
    ASSERT_TRUE(culled.ok());
    const test::Rgba background = test::pixelAt(*culled, 0, 0);
    EXPECT_EQ(test::coveredFraction(*culled, background), 0.0);

    renderer->setCullingCamera(std::nullopt);
    renderer->renderFrame(camera);
    auto visible = renderer->readImage();
    ASSERT_TRUE(visible.ok());
    EXPECT_GT(test::coveredFraction(*visible, background), 0.02);
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded,
              test::bundlesPerRecording(StrategyKind::GpuCullingBundles));
}

}  // namespace
}  // namespace encore::render
