// The visibility strategy where the device falls short: without AtomicVec2uMinMax the error names
// it; a visibility buffer past maxStorageBufferBindingSize is refused (and a resize past it);
// a target wider than half maxTextureDimension2D still renders at four samples.

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "VisibilityTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::render {
namespace {

using test::triangles;

constexpr std::uint32_t kWidth = test::kVisibilityWidth;
constexpr std::uint32_t kHeight = test::kVisibilityHeight;
constexpr std::array<std::uint32_t, 2> kSampleCounts = {1, 4};
const Camera kFront = test::frontCamera(float(kWidth) / float(kHeight));

TEST(VisibilityFeatureTest, WithoutTheFeatureTheErrorNamesIt) {
    ENCORE_REQUIRE_VULKAN(shared);
    auto context = gpu::Context::create();  // No requestVisibilityFeatures.
    ASSERT_TRUE(context.ok());
    ASSERT_FALSE(context->hasFeature(wgpu::FeatureName::AtomicVec2uMinMax));
    RendererOptions options = test::pixelTestOptions(kWidth, kHeight);
    options.environment = nullptr;  // The shared one belongs to the other device.
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok());
    const auto scene = triangles({{glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}});
    auto prepared = renderer->prepare(scene, StrategyKind::Visibility);
    ASSERT_FALSE(prepared.ok());
    EXPECT_EQ(prepared.error().code, ErrorCode::Unsupported);
    EXPECT_NE(prepared.error().message.find("AtomicVec2uMinMax"), std::string::npos);
}

TEST(VisibilityLimitsTest, AVisibilityBufferPastTheBindingLimitIsAnError) {
    ENCORE_REQUIRE_VULKAN(shared);
    // 128x96 at 4 samples needs 393,216 bytes of visibility buffer, at 1 sample 98,304.
    gpu::ContextOptions contextOptions;
    requestVisibilityFeatures(contextOptions);
    contextOptions.limitOverrides.maxStorageBufferBindingSize = 256 * 1024;
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok());
    const auto scene = triangles({{glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(0, 1, 0)}});
    for (std::uint32_t samples : kSampleCounts) {
        SCOPED_TRACE(std::to_string(samples) + " samples");
        RendererOptions options = test::pixelTestOptions(kWidth, kHeight, samples);
        options.environment = nullptr;  // The shared one belongs to the other device.
        auto renderer = Renderer::create(*context, options);
        ASSERT_TRUE(renderer.ok());
        auto prepared = renderer->prepare(scene, StrategyKind::Visibility);
        if (samples == 1) {
            ASSERT_TRUE(prepared.ok()) << prepared.error().message;
            // Growing the target past the limit is refused the same way.
            auto resized = renderer->resize(kWidth * 2, kHeight * 2);
            ASSERT_FALSE(resized.ok());
            EXPECT_NE(resized.error().message.find("maxStorageBufferBindingSize"),
                      std::string::npos);
            renderer->renderFrame(kFront);
            auto image = renderer->readImage();
            ASSERT_TRUE(image.ok());
            EXPECT_EQ(image->width, kWidth);
            EXPECT_GT(test::coveredFraction(*image, test::pixelAt(*image, 0, 0)), 0.01);
        } else {
            ASSERT_FALSE(prepared.ok());
            EXPECT_EQ(prepared.error().code, ErrorCode::LimitExceeded);
            EXPECT_NE(prepared.error().message.find("maxStorageBufferBindingSize"),
                      std::string::npos)
                << prepared.error().message;
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility limits").ok());
}

// The shaded colour is a layer per sample of the target's size: a target more than half
// maxTextureDimension2D wide (encore batch's strips of 12 views at 512 pixels) renders at four
// samples. Its former 2x2 texels per pixel made such a target fail to prepare.
TEST(VisibilityLimitsTest, AWideTargetRendersAtFourSamples) {
    ENCORE_REQUIRE_VULKAN(shared);
    gpu::ContextOptions contextOptions;
    requestVisibilityFeatures(contextOptions);
    contextOptions.limitOverrides.maxTextureDimension2D = kWidth + kWidth / 2;
    auto context = gpu::Context::create(contextOptions);
    ASSERT_TRUE(context.ok());
    const auto scene = triangles({{glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(0, 1, 0)}});
    RendererOptions options = test::pixelTestOptions(kWidth, kHeight, 4);
    options.environment = nullptr;  // The shared one belongs to the other device.
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok());
    auto prepared = renderer->prepare(scene, StrategyKind::Visibility);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    renderer->renderFrame(kFront);
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok());
    EXPECT_GT(test::coveredFraction(*image, test::pixelAt(*image, 0, 0)), 0.01);
    EXPECT_TRUE(context->checkNoErrors("wide target").ok());
}

TEST(VisibilityFeatureTest, TheTestContextHasTheFeature) {
    ENCORE_REQUIRE_VULKAN(context);
    // Mesa >= 25 lavapipe (and the H100's driver) report it with allow_unsafe_apis.
    EXPECT_TRUE(context->hasFeature(wgpu::FeatureName::AtomicVec2uMinMax))
        << context->adapterDescription().summary();
}

}  // namespace
}  // namespace encore::render
