// Render bundles: state reset around bundles, dynamic content without re-recording, re-recording
// when a referenced resource is replaced, and several views from one bundle.

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TextureFixtures.h"
#include "encore/render/Renderer.h"
#include "render/BundleRecorder.h"
#include "render/GpuScene.h"
#include "render/renderer/CreateStrategy.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

using test::frontCamera;

// Quads of width 0.8 at the given x centres, each with its own material colour.
scene::SceneData quadScene(const std::vector<std::pair<float, glm::vec4>>& quads) {
    test::GltfBuilder builder;
    std::vector<std::uint32_t> nodes;
    for (const auto& [x, color] : quads) {
        test::GltfBuilder::PrimitiveDesc primitive;
        primitive.attributes["POSITION"] = builder.addPositions(
            {{x - 0.4f, -0.4f, 0}, {x + 0.4f, -0.4f, 0}, {x + 0.4f, 0.4f, 0}, {x - 0.4f, 0.4f, 0}});
        primitive.attributes["NORMAL"] =
            builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
        primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
        primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        primitive.material = builder.addMaterial({.baseColor = color});
        nodes.push_back(builder.addNode({.mesh = builder.addMesh(primitive)}));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "quads.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

std::pair<std::uint32_t, std::uint32_t> pixelOf(const Camera& camera, const glm::vec3& point) {
    return test::pixelOf(camera, point, kSize, kSize);
}

// The dominant channel of a pixel: 0 red, 1 green, 2 blue, -1 background (dark grey).
int dominantChannel(const test::Rgba& pixel) {
    const int maxValue = std::max({pixel[0], pixel[1], pixel[2]});
    if (maxValue < 100) {
        return -1;
    }
    return pixel[0] == maxValue ? 0 : (pixel[1] == maxValue ? 1 : 2);
}

image::ImageRgba8 renderOnce(const scene::SceneData& scene,
                             StrategyKind kind,
                             const Camera& camera,
                             const glm::mat4* moveFirstInstance = nullptr) {
    gpu::Context* context = test::vulkanContext();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(scene, kind).ok());
    if (moveFirstInstance) {
        EXPECT_TRUE(renderer->updateInstance(0, *moveFirstInstance).ok());
    }
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// Two bundles in one pass, between direct draws: each bundle sets all of its state, and the
// direct draws after them set theirs again (executeBundles resets it).
TEST(BundleTest, TwoBundlesBetweenDirectDrawsInOnePass) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto sceneA = quadScene({{-1.5f, {1, 0, 0, 1}}});  // red, far left
    const auto sceneB = quadScene({{-0.5f, {0, 1, 0, 1}}});  // green
    const auto sceneC = quadScene({{0.5f, {0, 0, 1, 1}}});   // blue, drawn directly before
    const auto sceneD = quadScene({{1.5f, {1, 0, 0, 1}}});   // red, drawn directly after

    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const RenderSetup& setup = internals(*renderer).setup();
    std::vector<std::unique_ptr<GpuScene>> gpuScenes;  // Outlive the strategies.
    auto prepare = [&](const scene::SceneData& scene) {
        auto uploaded = GpuScene::create(setup, scene);
        EXPECT_TRUE(uploaded.ok());
        gpuScenes.push_back(std::move(*uploaded));
        auto strategy = createStrategy(StrategyKind::Materials);
        EXPECT_TRUE(strategy->prepare(setup, *gpuScenes.back()).ok());
        return strategy;
    };
    auto a = prepare(sceneA);
    auto b = prepare(sceneB);
    auto c = prepare(sceneC);
    auto d = prepare(sceneD);
    const Camera camera = frontCamera();
    setup.frame->update(context->queue(), camera, 0.0f);
    const FrameState frame{camera, {&camera, 1}, 0.0f};
    const RecordedBundle bundleA =
        recordBundle(setup, "bundle A", [&](RenderEncoder& encoder) { a->encode(encoder, frame); });
    const RecordedBundle bundleB =
        recordBundle(setup, "bundle B", [&](RenderEncoder& encoder) { b->encode(encoder, frame); });
    EXPECT_EQ(bundleA.contents.drawIndexed, 1u);
    EXPECT_EQ(bundleA.contents.setBindGroup, 3u);  // Frame, instances, material: all its state.

    wgpu::CommandEncoder commands = context->device().CreateCommandEncoder();
    auto color = renderer->target().colorAttachment({0.05, 0.05, 0.06, 1.0});
    auto depth = renderer->target().depthAttachment();
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    descriptor.depthStencilAttachment = &depth;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    DrawCounters counters;
    RenderEncoder encoder(pass, counters);
    c->encode(encoder, frame);
    const wgpu::RenderBundle bundles[] = {bundleA.bundle, bundleB.bundle};
    encoder.executeBundles(bundles);
    d->encode(encoder, frame);
    pass.End();
    wgpu::CommandBuffer commandBuffer = commands.Finish();
    context->queue().Submit(1, &commandBuffer);
    renderer->toneMapScene();
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_EQ(counters.executeBundles, 1u);
    EXPECT_EQ(counters.drawIndexed, 2u);  // The two direct draws.

    const std::pair<float, int> expected[] = {{-1.5f, 0}, {-0.5f, 1}, {0.5f, 2}, {1.5f, 0}};
    for (const auto& [x, channel] : expected) {
        const auto [px, py] = pixelOf(camera, {x, 0.0f, 0.0f});
        EXPECT_EQ(dominantChannel(test::pixelAt(*image, px, py)), channel) << "quad at x=" << x;
    }
    const auto [gapX, gapY] = pixelOf(camera, {0.0f, 0.0f, 0.0f});
    EXPECT_EQ(dominantChannel(test::pixelAt(*image, gapX, gapY)), -1) << "gap between quads";
    EXPECT_TRUE(context->checkNoErrors("two bundles").ok());
}

// Frame 2 moves the camera and a node through buffers: the bundle recorded for frame 1 is
// replayed unchanged and matches a freshly recorded direct pass of the new state.
TEST(BundleTest, CameraAndTransformChangesNeedNoReRecording) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = quadScene({{-0.5f, {1, 0, 0, 1}}, {0.5f, {0, 0, 1, 1}}});
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    renderer->renderFrame(frontCamera());
    ASSERT_TRUE(renderer->readImage().ok());
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, 1u);

    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.8f, -0.5f));
    const Camera secondCamera = frontCamera(1.0f, 0.3f);
    ASSERT_TRUE(renderer->updateInstance(0, moved).ok());
    const auto frame = renderer->renderFrame(secondCamera);
    auto second = renderer->readImage();
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, 1u)
        << "the bundle was re-recorded";
    EXPECT_EQ(frame.counters.executeBundles, 1u);
    EXPECT_EQ(frame.counters.drawCalls(), 0u);  // Every draw comes from the bundle.

    const auto fresh = renderOnce(scene, StrategyKind::Materials, secondCamera, &moved);
    EXPECT_EQ(test::differingPixels(*second, fresh), 0u);
    const auto unmoved = renderOnce(scene, StrategyKind::Materials, secondCamera);
    EXPECT_GT(test::differingPixels(*second, unmoved), 0u) << "the node did not move";
    EXPECT_TRUE(context->checkNoErrors("dynamic bundle").ok());
}

TEST(BundleTest, MaterialFactorChangesNeedNoReRecording) {
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = quadScene({{0.0f, {1, 0, 0, 1}}});
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    const Camera camera = frontCamera();
    renderer->renderFrame(camera);
    ASSERT_TRUE(renderer->readImage().ok());

    scene::Material green = scene.materials[0];
    green.baseColorFactor = {0, 1, 0, 1};
    ASSERT_TRUE(renderer->updateMaterial(scene::MaterialId{0u}, green).ok());
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok());
    const auto [x, y] = pixelOf(camera, {0, 0, 0});
    EXPECT_EQ(dominantChannel(test::pixelAt(*image, x, y)), 1);
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, 1u);
    EXPECT_FALSE(renderer->updateMaterial(scene::MaterialId{7u}, green).ok());
    // Adding an extension that chooses the pipelines is refused, naming it.
    scene::Material iridescent = green;
    iridescent.iridescence = scene::IridescenceExtension{};
    auto refused = renderer->updateMaterial(scene::MaterialId{0u}, iridescent);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("iridescence"), std::string::npos);
    EXPECT_TRUE(context->checkNoErrors("material factor").ok());
}

// Replacing a texture destroys the old one: executing the old bundle would be a validation
// error, so the strategy must notice and re-record.
TEST(BundleTest, ReplacedTextureReRecordsTheBundle) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = quadScene({{0.0f, {1, 1, 1, 1}}});
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    const Camera camera = frontCamera();
    auto solid = [](std::uint8_t r, std::uint8_t g, std::uint8_t b) {
        return test::solidSceneImage({r, g, b, 255});
    };
    ASSERT_TRUE(renderer->replaceBaseColorImage(scene::MaterialId{0u}, solid(255, 0, 0)).ok());
    renderer->renderFrame(camera);
    ASSERT_TRUE(renderer->readImage().ok());
    const auto recordedBefore = internals(*renderer).strategy()->report().bundlesRecorded;

    ASSERT_TRUE(renderer->replaceBaseColorImage(scene::MaterialId{0u}, solid(0, 0, 255)).ok());
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    ASSERT_TRUE(image.ok()) << image.error().message;  // A stale bundle fails here.
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, recordedBefore + 1);
    const auto [x, y] = pixelOf(camera, {0, 0, 0});
    EXPECT_EQ(dominantChannel(test::pixelAt(*image, x, y)), 2);
    EXPECT_TRUE(context->checkNoErrors("replaced texture").ok());
}

// Stereo: two cameras, one bundle replayed per view; each half equals a single-view render.
TEST(BundleTest, TwoViewsReplayOneBundle) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = quadScene({{-0.5f, {1, 0, 0, 1}}, {0.5f, {0, 0, 1, 1}}});
    auto stereo = Renderer::create(*context, test::pixelTestOptions(2 * kSize, kSize));
    ASSERT_TRUE(stereo.ok());
    ASSERT_TRUE(stereo->prepare(scene, StrategyKind::Bundles).ok());
    const Camera cameras[] = {frontCamera(1.0f, -0.1f), frontCamera(1.0f, 0.1f)};
    const auto frame = stereo->renderViews(cameras);
    auto both = stereo->readImage();
    ASSERT_TRUE(both.ok()) << both.error().message;
    EXPECT_EQ(frame.counters.executeBundles, 2u);  // One replay per view.
    EXPECT_EQ(internals(*stereo).strategy()->report().bundlesRecorded, 1u);

    for (int view = 0; view < 2; ++view) {
        const auto single = renderOnce(scene, StrategyKind::Materials, cameras[view]);
        std::size_t differing = 0;
        for (std::uint32_t y = 0; y < kSize; ++y) {
            for (std::uint32_t x = 0; x < kSize; ++x) {
                differing +=
                    test::pixelAt(*both, x + view * kSize, y) != test::pixelAt(single, x, y);
            }
        }
        EXPECT_EQ(differing, 0u) << "view " << view;
    }
    EXPECT_TRUE(context->checkNoErrors("stereo").ok());
}

}  // namespace
}  // namespace encore::render
