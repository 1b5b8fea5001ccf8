// The Animometer scene: call counts per mode, and the same pixels whether the draws are recorded
// directly or replayed from a bundle, and whether slots are bound by N groups or dynamic offsets.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "render/Animometer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 128;
constexpr std::uint32_t kTriangles = 100;
const test::Rgba kBackground = {0, 0, 0, 255};  // AnimometerScene::kClearColor.

AnimometerOptions smallOptions(bool bundle = false, bool dynamicOffsets = false) {
    AnimometerOptions options;
    options.triangles = kTriangles;
    options.bundle = bundle;
    options.dynamicOffsets = dynamicOffsets;
    options.width = kSize;
    options.height = kSize;
    options.seed = 7;
    return options;
}

// Renders one frame of a fresh scene at `time`.
image::ImageRgba8 renderAt(gpu::Context& context, const AnimometerOptions& options, float time) {
    shaders::ShaderLibrary shaders(context.device());
    auto scene = AnimometerScene::create(context, shaders, options);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    if (!scene.ok()) {
        return {};
    }
    scene->renderFrame(time);
    auto image = scene->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

TEST(AnimometerTest, DirectModeRecordsOneBindGroupAndDrawPerTriangle) {
    ENCORE_REQUIRE_VULKAN(context);
    shaders::ShaderLibrary shaders(context->device());
    auto scene = AnimometerScene::create(*context, shaders, smallOptions());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->describe(), "animometer 100 triangles, bind groups, direct");
    scene->renderFrame(0.5f);
    auto image = scene->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;

    const DrawCounters& counters = scene->lastFrameCounters();
    EXPECT_EQ(counters.draw, kTriangles);
    EXPECT_EQ(counters.setBindGroup, kTriangles + 1);  // Group 1 per triangle + group 0 once.
    EXPECT_EQ(counters.setPipeline, 1u);
    EXPECT_EQ(counters.setVertexBuffer, 1u);
    EXPECT_EQ(counters.triangles, kTriangles);
    EXPECT_EQ(counters.executeBundles, 0u);
    EXPECT_EQ(scene->bundleContents(), DrawCounters{});
    EXPECT_GT(test::coveredFraction(*image, kBackground), 0.01);
    EXPECT_TRUE(context->checkNoErrors("animometer direct").ok());
}

TEST(AnimometerTest, BundleReplaysTheSameDrawsAndPixels) {
    ENCORE_REQUIRE_VULKAN(context);
    shaders::ShaderLibrary shaders(context->device());
    auto scene = AnimometerScene::create(*context, shaders, smallOptions(true));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->describe(), "animometer 100 triangles, bind groups, bundle");
    EXPECT_EQ(scene->bundleContents().draw, kTriangles);
    EXPECT_EQ(scene->bundleContents().setBindGroup, kTriangles + 1);
    scene->renderFrame(0.5f);
    auto bundled = scene->readImage();
    ASSERT_TRUE(bundled.ok()) << bundled.error().message;

    const DrawCounters& counters = scene->lastFrameCounters();
    EXPECT_EQ(counters.executeBundles, 1u);
    EXPECT_EQ(counters.draw, 0u);
    EXPECT_EQ(counters.apiCalls(), 1u);
    const auto direct = renderAt(*context, smallOptions(), 0.5f);
    EXPECT_GT(test::coveredFraction(*bundled, kBackground), 0.01);
    EXPECT_EQ(test::differingPixels(*bundled, direct), 0u);

    // The bundle stays valid as time moves on: a later frame matches a direct one too.
    scene->renderFrame(2.25f);
    auto later = scene->readImage();
    ASSERT_TRUE(later.ok()) << later.error().message;
    EXPECT_EQ(test::differingPixels(*later, renderAt(*context, smallOptions(), 2.25f)), 0u);
    EXPECT_TRUE(context->checkNoErrors("animometer bundle").ok());
}

TEST(AnimometerTest, DynamicOffsetsRenderTheSameImageAsBindGroups) {
    ENCORE_REQUIRE_VULKAN(context);
    shaders::ShaderLibrary shaders(context->device());
    auto scene = AnimometerScene::create(*context, shaders, smallOptions(false, true));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->describe(), "animometer 100 triangles, dynamic offsets, direct");
    scene->renderFrame(1.5f);
    auto dynamic = scene->readImage();
    ASSERT_TRUE(dynamic.ok()) << dynamic.error().message;
    EXPECT_EQ(scene->lastFrameCounters().setBindGroup, kTriangles + 1);
    EXPECT_EQ(scene->lastFrameCounters().draw, kTriangles);

    const auto groups = renderAt(*context, smallOptions(), 1.5f);
    EXPECT_GT(test::coveredFraction(*dynamic, kBackground), 0.01);
    EXPECT_EQ(test::differingPixels(*dynamic, groups), 0u);
    const auto dynamicBundle = renderAt(*context, smallOptions(true, true), 1.5f);
    EXPECT_EQ(test::differingPixels(dynamicBundle, groups), 0u);
    EXPECT_TRUE(context->checkNoErrors("animometer dynamic offsets").ok());
}

TEST(AnimometerTest, TimeAnimatesTheTriangles) {
    ENCORE_REQUIRE_VULKAN(context);
    shaders::ShaderLibrary shaders(context->device());
    auto scene = AnimometerScene::create(*context, shaders, smallOptions(true));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    scene->renderFrame(0.0f);
    auto first = scene->readImage();
    ASSERT_TRUE(first.ok()) << first.error().message;
    scene->renderFrame(1.0f);
    auto second = scene->readImage();
    ASSERT_TRUE(second.ok()) << second.error().message;
    // Every triangle turns by at least 0.2 rad per second: far more than a few pixels change.
    EXPECT_GT(test::differingPixels(*first, *second), std::size_t(kSize * kSize / 100));

    // A different seed places the triangles elsewhere.
    AnimometerOptions otherSeed = smallOptions(true);
    otherSeed.seed = 8;
    EXPECT_GT(test::differingPixels(*first, renderAt(*context, otherSeed, 0.0f)), 0u);
    EXPECT_TRUE(context->checkNoErrors("animometer time").ok());
}

TEST(AnimometerTest, RefusesTriangleCountsOutsideTheLimits) {
    ENCORE_REQUIRE_VULKAN(context);
    shaders::ShaderLibrary shaders(context->device());
    AnimometerOptions options = smallOptions();
    options.triangles = 0;
    auto none = AnimometerScene::create(*context, shaders, options);
    ASSERT_FALSE(none.ok());
    EXPECT_EQ(none.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(none.error().message.find("(got 0)"), std::string::npos) << none.error().message;

    options.triangles = kMaxAnimometerTriangles + 1;
    auto tooMany = AnimometerScene::create(*context, shaders, options);
    ASSERT_FALSE(tooMany.ok());
    EXPECT_EQ(tooMany.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(tooMany.error().message.find("(got 1000001)"), std::string::npos)
        << tooMany.error().message;

    options.triangles = kTriangles;
    options.width = 0;
    auto noSize = AnimometerScene::create(*context, shaders, options);
    ASSERT_FALSE(noSize.ok());
    EXPECT_EQ(noSize.error().code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(context->checkNoErrors("animometer limits").ok());
}

}  // namespace
}  // namespace encore::render
