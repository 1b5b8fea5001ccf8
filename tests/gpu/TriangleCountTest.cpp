// Triangle counters: what the frame's draws could draw (FrameResult::trianglesSubmitted, on the
// CPU) and what the GPU culling pass let through (Renderer::takeDrawnTriangles). With the whole
// scene in view the GPU count equals the CPU sum; looking away it is 0; half the scene behind
// the camera gives a count in between; the history holds one value per frame.

#include <gtest/gtest.h>

#include <algorithm>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/CameraPath.h"
#include "render/culling/GpuCuller.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

scene::SceneData generated(scene::SceneLayout layout, std::uint32_t objects) {
    scene::GeneratorOptions options;
    options.layout = layout;
    options.objectCount = objects;
    options.meshCount = 7;  // Boxes, spheres, cylinders, cones, tori of two tessellations.
    options.materialCount = 3;
    options.tessellation = 4;
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "generated.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// The triangles of every instance of the scene, from the CPU data alone.
std::uint64_t sceneTriangles(const scene::SceneData& scene) {
    std::uint64_t triangles = 0;
    for (const auto& instance : scene.instances) {
        for (const auto& primitive : scene.meshes[instance.mesh.index()].primitives) {
            const std::uint64_t elements = primitive.indices
                                               ? scene.accessors[primitive.indices->index()].count
                                               : primitive.vertexCount;
            triangles += triangleCount(primitive.topology, elements);
        }
    }
    return triangles;
}

// Renders one frame per camera with counting on and returns the drawn counts.
std::vector<std::uint64_t> drawnTriangles(Renderer& renderer, std::span<const Camera> cameras) {
    renderer.setTriangleCounting(true);
    for (const Camera& camera : cameras) {
        renderer.renderFrame(camera);
    }
    auto drawn = renderer.takeDrawnTriangles();
    EXPECT_TRUE(drawn.ok()) << drawn.error().message;
    return drawn.ok() ? *drawn : std::vector<std::uint64_t>{};
}

class TriangleCountTest : public ::testing::TestWithParam<StrategyKind> {};

TEST_P(TriangleCountTest, AllInViewNoneInViewAndHalfBehindTheCamera) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generated(scene::SceneLayout::Grid, 300);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    renderer->setCullingOptions(
        {.occlusion = false, .levelsOfDetail = false});  // Frustum culling: exact expectations.
    ASSERT_TRUE(renderer->prepare(scene, GetParam()).ok());
    const GpuCuller* culler = internals(*renderer).strategy()->report().culler;
    ASSERT_NE(culler, nullptr);
    const std::uint64_t total = sceneTriangles(scene);
    EXPECT_EQ(submittedTriangles(culler->draws()), total);

    const Camera whole = Camera::framing(scene.bounds, 1.0f);
    const Camera away = Camera::lookAt({0.0f, 50.0f, 0.0f}, {0.0f, 100.0f, 0.0f},
                                       glm::radians(40.0f), 1.0f, 0.1f, 100.0f);
    // From the middle of the grid's west edge towards its middle, with a field of view of
    // nearly 180 degrees: the near plane through the camera cuts off nothing behind it (there
    // is nothing), then from its middle: the half behind is culled.
    const glm::vec3 center = scene.bounds.center();
    const Camera fromMiddle = Camera::lookAt(center, center + glm::vec3(1.0f, 0.0f, 0.0f),
                                             glm::radians(170.0f), 1.0f, 0.01f, 1000.0f);
    const std::vector<Camera> cameras = {whole, away, fromMiddle, whole};
    const auto drawn = drawnTriangles(*renderer, cameras);
    ASSERT_EQ(drawn.size(), 4u);
    EXPECT_EQ(drawn[0], total);
    EXPECT_EQ(drawn[1], 0u);
    EXPECT_GT(drawn[2], total / 4);
    EXPECT_LT(drawn[2], total * 3 / 4);
    EXPECT_EQ(drawn[3], total);

    // The CPU side: every frame could draw everything.
    EXPECT_EQ(renderer->renderFrame(away).trianglesSubmitted, total);
    // A take starts a new history: only the frame since.
    const auto next = renderer->takeDrawnTriangles();
    ASSERT_TRUE(next.ok());
    EXPECT_EQ(next->size(), 1u);
    renderer->setTriangleCounting(false);
    renderer->renderFrame(whole);
    EXPECT_TRUE(renderer->takeDrawnTriangles()->empty());
    EXPECT_TRUE(context->checkNoErrors("triangle counting").ok());
}

// Along the fly-through the culling pass draws part of what the draws could draw.
TEST_P(TriangleCountTest, TheFlythroughCullsPartOfTheLattice) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.layout = scene::SceneLayout::Lattice;
    options.objectCount = 500;
    options.meshCount = 7;
    options.materialCount = 3;
    options.tessellation = 4;
    auto glb = scene::generateSceneGlb(options);
    ASSERT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "lattice.glb");
    ASSERT_TRUE(scene.ok());
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(*scene, GetParam()).ok());
    const CameraPath path = CameraPath::flythrough(options);
    std::vector<Camera> cameras;
    for (std::uint32_t frame = 0; frame < 4; ++frame) {
        cameras.push_back(path.camera(frame, 4, 1.0f));
    }
    const auto drawn = drawnTriangles(*renderer, cameras);
    ASSERT_EQ(drawn.size(), 4u);
    const std::uint64_t total = sceneTriangles(*scene);
    for (const std::uint64_t count : drawn) {
        EXPECT_GT(count, 0u);
        EXPECT_LT(count, total / 2);
    }
    EXPECT_TRUE(context->checkNoErrors("fly-through").ok());
}

INSTANTIATE_TEST_SUITE_P(DirectAndBundled,
                         TriangleCountTest,
                         ::testing::Values(StrategyKind::GpuCulling,
                                           StrategyKind::GpuCullingBundles),
                         [](const auto& info) { return test::strategyTestName(info.param); });

// Strategies without GPU culling submit what they draw and have no drawn count; they submit as
// many triangles as the culling strategies.
TEST(TriangleCountTest, StrategiesWithoutCullingSubmitTheSameTriangles) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generated(scene::SceneLayout::City, 60);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    for (const StrategyKind kind :
         {StrategyKind::Naive, StrategyKind::Bundles, StrategyKind::GpuCulling}) {
        SCOPED_TRACE(strategyName(kind));
        ASSERT_TRUE(renderer->prepare(scene, kind).ok());
        renderer->setTriangleCounting(true);
        EXPECT_EQ(renderer->renderFrame(camera).trianglesSubmitted, sceneTriangles(scene));
        const auto drawn = renderer->takeDrawnTriangles();
        ASSERT_TRUE(drawn.ok());
        EXPECT_EQ(drawn->size(), kind == StrategyKind::GpuCulling ? 1u : 0u);
    }
    EXPECT_TRUE(context->checkNoErrors("strategies").ok());
}

}  // namespace
}  // namespace encore::render
