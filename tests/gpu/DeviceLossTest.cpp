// A lost device (Dawn's Device::ForceLoss) is survivable: rendering on the lost device fails
// cleanly, and the renderer rebuilds every GPU resource on a new device from CPU data, after
// which frames equal those from before the loss.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "scene/CrowdGenerator.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

void waitForLoss(gpu::Context& context) {
    for (int attempt = 0; attempt < 200 && !context.deviceLost(); ++attempt) {
        context.instance().ProcessEvents();
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

class DeviceLossTest : public ::testing::TestWithParam<StrategyKind> {};

TEST_P(DeviceLossTest, RendererRebuildsOnANewDeviceAndDrawsTheSameFrame) {
    // An own context: losing the process-wide one would take the other tests with it.
    auto context = gpu::Context::create();
    ASSERT_TRUE(context.ok()) << context.error().message;
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);

    scene::GeneratorOptions generator;
    generator.objectCount = 40;
    generator.meshCount = 3;
    generator.materialCount = 4;
    auto glb = scene::generateSceneGlb(generator);
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto scene = scene::loadSceneFromMemory(*glb, {}, "generated.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.environment = nullptr;  // The shared test environment lives on another device.
    options.environmentOptions = test::testEnvironmentOptions();
    options.toneMapping.exposure = 1.5f;
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    ASSERT_TRUE(renderer->prepare(*scene, GetParam()).ok());
    renderer->setLighting({.environmentIntensity = 0.7f});
    const Camera camera = Camera::framing(scene->bounds, 1.0f);
    renderer->renderFrame(camera);
    auto before = renderer->readImage();
    ASSERT_TRUE(before.ok()) << before.error().message;

    context->device().ForceLoss(wgpu::DeviceLostReason::Unknown, "lost on purpose by a test");
    waitForLoss(*context);
    ASSERT_TRUE(context->deviceLost());
    // Work on the lost device is dropped, not a crash; reading back reports the failure.
    renderer->renderFrame(camera);
    EXPECT_FALSE(renderer->readImage().ok());

    auto recovered = renderer->recoverFromDeviceLoss();
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    EXPECT_FALSE(context->deviceLost());
    for (int frame = 0; frame < 3; ++frame) {
        renderer->renderFrame(camera);
    }
    auto after = renderer->readImage();
    ASSERT_TRUE(after.ok()) << after.error().message;
    EXPECT_EQ(test::differingPixels(*before, *after, 0), 0u)
        << "exposure, lighting, scene and strategy must survive the loss";
    EXPECT_TRUE(context->checkNoErrors("rendering after recovery").ok());
}

INSTANTIATE_TEST_SUITE_P(Strategies,
                         DeviceLossTest,
                         ::testing::Values(StrategyKind::Naive,
                                           StrategyKind::Bundles,
                                           StrategyKind::GpuCullingBundles),
                         [](const auto& info) { return test::strategyTestName(info.param); });

// An animated scene comes back at the time it was playing, with its selection, evaluated where
// it was (CPU or GPU), not in its rest pose.
class AnimatedDeviceLossTest : public ::testing::TestWithParam<AnimationEvaluation> {};

TEST_P(AnimatedDeviceLossTest, TheAnimationResumesWhereItWas) {
    auto context = gpu::Context::create();
    ASSERT_TRUE(context.ok()) << context.error().message;
    ASSERT_EQ(context->adapterDescription().backend, wgpu::BackendType::Vulkan);
    auto glb = scene::generateCrowdGlb({.characters = 9});
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto scene = scene::loadSceneFromMemory(*glb, {}, "crowd.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.environment = nullptr;
    options.environmentOptions = test::testEnvironmentOptions();
    options.animation = GetParam();
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    ASSERT_TRUE(renderer->prepare(*scene, StrategyKind::Bundles).ok());
    const Camera camera = Camera::framing(scene->bounds, 1.0f);
    renderer->renderFrame(camera);
    auto rest = renderer->readImage();
    ASSERT_TRUE(rest.ok()) << rest.error().message;
    ASSERT_TRUE(renderer->selectAnimation("sway 4").ok());  // The middle character alone.
    ASSERT_TRUE(renderer->setAnimationTime(0.3).ok());      // 0.78 s into its sway.
    renderer->renderFrame(camera);
    auto before = renderer->readImage();
    ASSERT_TRUE(before.ok()) << before.error().message;
    ASSERT_GT(test::differingPixels(*rest, *before, 2), 0u) << "the crowd does not move";

    context->device().ForceLoss(wgpu::DeviceLostReason::Unknown, "lost on purpose by a test");
    waitForLoss(*context);
    ASSERT_TRUE(context->deviceLost());
    auto recovered = renderer->recoverFromDeviceLoss();
    ASSERT_TRUE(recovered.ok()) << recovered.error().message;
    renderer->renderFrame(camera);
    auto after = renderer->readImage();
    ASSERT_TRUE(after.ok()) << after.error().message;
    EXPECT_EQ(test::differingPixels(*before, *after, 0), 0u)
        << "the animation must resume at its time, not at rest";
    EXPECT_TRUE(context->checkNoErrors("animating after recovery").ok());
}

INSTANTIATE_TEST_SUITE_P(Evaluations,
                         AnimatedDeviceLossTest,
                         ::testing::Values(AnimationEvaluation::Cpu, AnimationEvaluation::Gpu),
                         [](const auto& info) {
                             return std::string(animationEvaluationName(info.param));
                         });

}  // namespace
}  // namespace encore::render
