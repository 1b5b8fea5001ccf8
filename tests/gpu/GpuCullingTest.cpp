// GPU culling: the GPU's visible counts equal a CPU frustum test of the same instances, the
// culled image equals the unculled one for any view, nothing breaks when nothing is visible,
// moved instances are re-tested, and Dawn's IndirectFirstInstance trap is real (and avoided).

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/culling/GpuCuller.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 96;

scene::SceneData gridScene() {
    scene::GeneratorOptions options;
    options.objectCount = 400;
    options.meshCount = 5;
    options.materialCount = 3;
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "grid.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// A camera inside the grid looking along +X at low height: most objects are behind it or
// outside the narrow field of view.
Camera partialCamera() {
    return Camera::lookAt({-5.0f, 1.5f, -3.0f}, {10.0f, 0.0f, 2.0f}, glm::radians(40.0f), 1.0f,
                          0.1f, 100.0f);
}

// An independent CPU frustum test of the instances' spheres (planes from the matrix rows), with
// `worlds` per scene instance.
std::vector<std::uint32_t> cpuInstanceCounts(const GpuCuller& culler,
                                             const Camera& camera,
                                             const scene::SceneData& scene) {
    const std::vector<std::uint32_t> slots = instanceSlots(scene);
    std::vector<glm::mat4> worldOfSlot(slots.size());
    for (std::size_t instance = 0; instance < slots.size(); ++instance) {
        worldOfSlot[slots[instance]] = scene.instances[instance].world;
    }
    const glm::mat4 m = camera.projection * camera.view;
    std::vector<glm::vec4> planes;
    for (int axis = 0; axis < 2; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            planes.push_back(glm::row(m, 3) + sign * glm::row(m, axis));
        }
    }
    planes.push_back(glm::row(m, 2));
    planes.push_back(glm::row(m, 3) - glm::row(m, 2));
    std::vector<std::uint32_t> counts;
    for (const CulledDraw& draw : culler.draws()) {
        std::uint32_t visible = 0;
        for (std::uint32_t slot = draw.instances.first;
             slot < draw.instances.first + draw.instances.count; ++slot) {
            const auto spheres = culler.bounds().worldSpheres(slot, worldOfSlot[slot], {}, {});
            EXPECT_EQ(spheres.size(), 1u);
            const Sphere& sphere = spheres.front();
            bool inside = true;
            for (const glm::vec4& plane : planes) {
                const float distance = (glm::dot(glm::vec3(plane), glm::vec3(sphere)) + plane.w) /
                                       glm::length(glm::vec3(plane));
                inside = inside && distance >= -sphere.w;
            }
            visible += inside;
        }
        counts.push_back(visible);
    }
    return counts;
}

image::ImageRgba8 render(Renderer& renderer,
                         const scene::SceneData& scene,
                         StrategyKind kind,
                         const Camera& camera) {
    EXPECT_TRUE(renderer.prepare(scene, kind).ok());
    renderer.renderFrame(camera);
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

class GpuCullingTest : public ::testing::TestWithParam<StrategyKind> {};

TEST_P(GpuCullingTest, VisibleCountsEqualACpuFrustumTestAndTheImageEqualsUnculled) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera camera = partialCamera();
    const auto unculled = render(*renderer, scene, StrategyKind::Materials, camera);
    const auto culled = render(*renderer, scene, GetParam(), camera);
    EXPECT_EQ(test::differingPixels(unculled, culled), 0u);
    EXPECT_GT(test::coveredFraction(culled, test::pixelAt(culled, 0, kSize - 1)), 0.01);

    const GpuCuller* culler = internals(*renderer).strategy()->report().culler;
    ASSERT_NE(culler, nullptr);
    const auto gpuCounts = test::culledInstanceCounts(*context, *culler);
    const auto cpuCounts = cpuInstanceCounts(*culler, camera, scene);
    EXPECT_EQ(gpuCounts, cpuCounts);
    std::uint64_t visible = 0;
    for (auto count : gpuCounts) {
        visible += count;
    }
    EXPECT_GT(visible, 0u);
    EXPECT_LT(visible, scene.instances.size()) << "the view should cull part of the grid";
    EXPECT_TRUE(context->checkNoErrors("culling").ok());
}

TEST_P(GpuCullingTest, WholeSceneInViewDrawsEverything) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    const auto unculled = render(*renderer, scene, StrategyKind::Materials, camera);
    const auto culled = render(*renderer, scene, GetParam(), camera);
    EXPECT_EQ(test::differingPixels(unculled, culled), 0u);
    std::uint64_t visible = 0;
    for (auto count :
         test::culledInstanceCounts(*context, *internals(*renderer).strategy()->report().culler)) {
        visible += count;
    }
    EXPECT_EQ(visible, scene.instances.size());
}

TEST_P(GpuCullingTest, NothingVisibleDrawsNothingAndStaysValid) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera away = Camera::lookAt({0.0f, 50.0f, 0.0f}, {0.0f, 100.0f, 0.0f},
                                       glm::radians(40.0f), 1.0f, 0.1f, 100.0f);
    const auto image = render(*renderer, scene, GetParam(), away);
    EXPECT_EQ(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.0);
    for (auto count :
         test::culledInstanceCounts(*context, *internals(*renderer).strategy()->report().culler)) {
        EXPECT_EQ(count, 0u);
    }
    EXPECT_TRUE(context->checkNoErrors("nothing visible").ok());
}

// Moving an instance updates its bounding sphere: a node moved far outside the view is culled
// in the next frame without re-recording anything.
TEST_P(GpuCullingTest, MovedInstancesAreCulledWhereTheyAreNow) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    render(*renderer, scene, GetParam(), camera);
    const auto recorded = internals(*renderer).strategy()->report().bundlesRecorded;
    const glm::mat4 farAway = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1000.0f, 0.0f));
    for (std::size_t instance = 0; instance < 10; ++instance) {
        ASSERT_TRUE(renderer->updateInstance(instance, farAway).ok());
    }
    renderer->renderFrame(camera);
    ASSERT_TRUE(renderer->readImage().ok());
    std::uint64_t visible = 0;
    for (auto count :
         test::culledInstanceCounts(*context, *internals(*renderer).strategy()->report().culler)) {
        visible += count;
    }
    EXPECT_EQ(visible, scene.instances.size() - 10);
    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, recorded);
}

// A frame of several views (`render --views`, batch strips) culls once for all of them: it must
// keep what any of its views sees, not only what the first one does.
TEST_P(GpuCullingTest, AMultiViewFrameKeepsWhatEveryViewSees) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(2 * kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    // From the middle of the grid, looking opposite ways: neither frustum holds the other's
    // objects.
    const glm::vec3 eye = scene.bounds.center() + glm::vec3(0.0f, 1.5f, 0.0f);
    const Camera views[] = {Camera::lookAt(eye, eye + glm::vec3(1.0f, -0.1f, 0.3f),
                                           glm::radians(40.0f), 1.0f, 0.1f, 100.0f),
                            Camera::lookAt(eye, eye - glm::vec3(1.0f, 0.1f, 0.3f),
                                           glm::radians(40.0f), 1.0f, 0.1f, 100.0f)};
    auto renderViews = [&](StrategyKind kind) {
        EXPECT_TRUE(renderer->prepare(scene, kind).ok());
        renderer->renderViews(views);
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok()) << image.error().message;
        return image.ok() ? std::move(*image) : image::ImageRgba8{};
    };
    const auto unculled = renderViews(StrategyKind::Materials);
    const auto culled = renderViews(GetParam());
    ASSERT_EQ(culled.width, 2 * kSize);
    EXPECT_EQ(test::differingPixels(unculled, culled), 0u);
    const auto background = test::pixelAt(unculled, 0, 0);
    for (std::uint32_t view = 0; view < 2; ++view) {
        std::size_t covered = 0;
        for (std::uint32_t y = 0; y < kSize; ++y) {
            for (std::uint32_t x = view * kSize; x < (view + 1) * kSize; ++x) {
                covered += test::pixelAt(unculled, x, y) != background;
            }
        }
        EXPECT_GT(covered, kSize * kSize / 100)
            << "view " << view << " should show part of the grid";
    }
    EXPECT_TRUE(context->checkNoErrors("multi-view culling").ok());
}

INSTANTIATE_TEST_SUITE_P(DirectAndBundled,
                         GpuCullingTest,
                         ::testing::Values(StrategyKind::GpuCulling,
                                           StrategyKind::GpuCullingBundles),
                         [](const auto& info) { return test::strategyTestName(info.param); });

// Dawn's indirect-draw validation zeroes any draw whose firstInstance is non-zero unless the
// device has IndirectFirstInstance (Encore does not request it). The draw vanishes without an
// error: this test shows the trap, which is why the culled draws keep firstInstance 0.
TEST(GpuCullingTrapTest, NonZeroFirstInstanceVanishesWithoutTheFeature) {
    ENCORE_REQUIRE_VULKAN(context);
    ASSERT_FALSE(context->hasFeature(wgpu::FeatureName::IndirectFirstInstance));
    const auto scene = gridScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    const auto full = render(*renderer, scene, StrategyKind::GpuCulling, camera);
    const GpuCuller* culler = internals(*renderer).strategy()->report().culler;
    ASSERT_NE(culler, nullptr);
    // Set firstInstance of every draw to 1 (the reset only rewrites instanceCount).
    for (std::size_t draw = 0; draw < culler->draws().size(); ++draw) {
        const std::uint32_t one = 1;
        context->queue().WriteBuffer(culler->indirectArguments(),
                                     culler->argumentsOffset(draw) + 16, &one, sizeof(one));
    }
    renderer->renderFrame(camera);
    auto vanished = renderer->readImage();
    ASSERT_TRUE(vanished.ok()) << vanished.error().message;  // No validation error either.
    EXPECT_GT(test::coveredFraction(full, test::pixelAt(full, 0, 0)), 0.01);
    EXPECT_EQ(test::coveredFraction(*vanished, test::pixelAt(*vanished, 0, 0)), 0.0)
        << "every draw with firstInstance 1 should have been skipped";
}

}  // namespace
}  // namespace encore::render
