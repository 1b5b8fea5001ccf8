// Levels of detail chosen by the culling pass: along the fly-through through a lattice of
// finely tessellated objects, the LOD frame stays within SSIM 0.98 of the full-detail frame,
// draws fewer triangles, draws distant instances at coarser levels, and never records its bundles
// again; a threshold too small for any level draws exactly the full-detail frame.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <span>
#include <vector>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "image/ImageCompare.h"
#include "render/CameraPath.h"
#include "render/culling/GpuCuller.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

// SSIM compares 11x11 windows: at 160x96 the lattice's distant objects are a few pixels wide and a
// one-pixel silhouette change is a large part of a window (SSIM 0.94 at the default one-pixel
// error, 0.97 at 320x192); at 640x360 the same error keeps every frame above 0.98.
constexpr std::uint32_t kWidth = 640;
constexpr std::uint32_t kHeight = 360;
constexpr std::uint32_t kFrames = 4;

scene::GeneratorOptions latticeOptions() {
    scene::GeneratorOptions options;
    options.layout = scene::SceneLayout::Lattice;
    options.objectCount = 800;
    options.meshCount = 6;
    options.materialCount = 3;
    options.tessellation = 24;  // Fine enough for the simplifier to find levels.
    return options;
}

scene::SceneData lattice() {
    auto glb = scene::generateSceneGlb(latticeOptions());
    EXPECT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "lattice.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

RendererOptions shadedOptions(bool levelsOfDetail, float lodErrorPixels = 1.0f) {
    RendererOptions options =
        test::pixelTestOptions(kWidth, kHeight, 1, render::DebugChannel::Shaded);
    options.culling.levelsOfDetail = levelsOfDetail;
    options.culling.lodErrorPixels = lodErrorPixels;
    return options;
}

image::ImageRgba8 readImage(Renderer& renderer) {
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// Instances drawn at levels other than level 0, over both phases.
std::uint64_t coarserInstances(gpu::Context& context, const GpuCuller& culler) {
    std::uint64_t total = 0;
    for (const auto& levels : test::culledCountsByLevel(context, culler)) {
        for (std::size_t level = 1; level < levels.size(); ++level) {
            total += levels[level][0] + levels[level][1];
        }
    }
    return total;
}

TEST(LevelOfDetailTest, TheFlythroughKeepsItsLookWithFewerTriangles) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = lattice();
    bool anyLevels = false;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            anyLevels = anyLevels || !primitive.levels.empty();
        }
    }
    ASSERT_TRUE(anyLevels) << "the loader should have built levels of detail";
    auto full = Renderer::create(*context, shadedOptions(false));
    auto detailed = Renderer::create(*context, shadedOptions(true));
    ASSERT_TRUE(full.ok() && detailed.ok());
    ASSERT_TRUE(full->prepare(scene, StrategyKind::GpuCullingBundles).ok());
    ASSERT_TRUE(detailed->prepare(scene, StrategyKind::GpuCullingBundles).ok());
    const CameraPath path = CameraPath::flythrough(latticeOptions());
    full->setTriangleCounting(true);
    detailed->setTriangleCounting(true);
    std::uint64_t recorded = 0;
    std::uint64_t coarser = 0;
    for (std::uint32_t frame = 0; frame < kFrames; ++frame) {
        const Camera camera = path.camera(frame, kFrames, float(kWidth) / float(kHeight));
        full->renderFrame(camera);
        detailed->renderFrame(camera);
        const auto expected = readImage(*full);
        const auto image = readImage(*detailed);
        auto ssim = image::ssimLuminance(expected, image);
        ASSERT_TRUE(ssim.ok());
        EXPECT_GE(*ssim, 0.98) << "frame " << frame;
        coarser += coarserInstances(*context, *internals(*detailed).strategy()->report().culler);
        if (frame == 0) {
            recorded = internals(*detailed).strategy()->report().bundlesRecorded;
        }
    }
    EXPECT_EQ(internals(*detailed).strategy()->report().bundlesRecorded, recorded);
    EXPECT_GT(coarser, 0u) << "distant instances should be drawn at coarser levels";
    const auto fullTriangles = full->takeDrawnTriangles();
    const auto lodTriangles = detailed->takeDrawnTriangles();
    ASSERT_TRUE(fullTriangles.ok() && lodTriangles.ok());
    ASSERT_EQ(fullTriangles->size(), kFrames);
    ASSERT_EQ(lodTriangles->size(), kFrames);
    for (std::uint32_t frame = 0; frame < kFrames; ++frame) {
        EXPECT_LT((*lodTriangles)[frame], (*fullTriangles)[frame]) << "frame " << frame;
    }
    EXPECT_TRUE(context->checkNoErrors("levels of detail").ok());
}

// With a threshold no level's error fits under, every instance is drawn at level 0: the same
// pixels as with levels of detail off.
TEST(LevelOfDetailTest, ATinyThresholdDrawsFullDetail) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = lattice();
    auto full = Renderer::create(*context, shadedOptions(false));
    auto tiny = Renderer::create(*context, shadedOptions(true, 1e-6f));
    ASSERT_TRUE(full.ok() && tiny.ok());
    ASSERT_TRUE(full->prepare(scene, StrategyKind::GpuCulling).ok());
    ASSERT_TRUE(tiny->prepare(scene, StrategyKind::GpuCulling).ok());
    const Camera camera =
        CameraPath::flythrough(latticeOptions()).camera(1, kFrames, float(kWidth) / float(kHeight));
    full->renderFrame(camera);
    tiny->renderFrame(camera);
    EXPECT_EQ(test::differingPixels(readImage(*full), readImage(*tiny), 0), 0u);
    EXPECT_EQ(coarserInstances(*context, *internals(*tiny).strategy()->report().culler), 0u);
}

// Instances drawn at level 0 of primitives that have coarser levels, over both phases.
std::uint64_t finestInstances(gpu::Context& context, const GpuCuller& culler) {
    std::uint64_t total = 0;
    for (const auto& levels : test::culledCountsByLevel(context, culler)) {
        if (levels.size() > 1) {
            total += levels[0][0] + levels[0][1];
        }
    }
    return total;
}

// A gpu-culling-bundles renderer with levels of detail after one frame of `views` side by side,
// each `viewWidth` x kHeight.
Result<Renderer> renderedViews(gpu::Context& context,
                               const scene::SceneData& scene,
                               std::span<const Camera> views,
                               std::uint32_t viewWidth) {
    RendererOptions options = shadedOptions(true);
    options.target.width = viewWidth * std::uint32_t(views.size());
    auto renderer = Renderer::create(context, options);
    if (!renderer) {
        return renderer;
    }
    if (auto prepared = renderer->prepare(scene, StrategyKind::GpuCullingBundles); !prepared) {
        return prepared.error();
    }
    renderer->renderViews(views);
    if (auto image = renderer->readImage(); !image) {
        return image.error();
    }
    return renderer;
}

// One cull serves all views of a multi-view frame: each instance gets a level at least as fine
// as the nearest view needs, whichever view comes first.
TEST(LevelOfDetailTest, AMultiViewFrameChoosesLevelsForItsNearestView) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = lattice();
    const float aspect = float(kWidth) / float(kHeight);
    // Far enough back that no instance needs level 0 there.
    const glm::vec3 center = scene.bounds.center();
    const Camera far =
        Camera::lookAt(center + glm::vec3(0.0f, 0.5f, 1.0f) * 12.0f * scene.bounds.radius(), center,
                       glm::radians(40.0f), aspect, 1.0f, 1000.0f);
    const Camera near = CameraPath::flythrough(latticeOptions()).camera(1, kFrames, aspect);
    auto finestFor = [&](std::span<const Camera> views) -> std::uint64_t {
        auto renderer = renderedViews(*context, scene, views, kWidth);
        EXPECT_TRUE(renderer.ok()) << renderer.error().message;
        return renderer.ok()
                   ? finestInstances(*context, *internals(*renderer).strategy()->report().culler)
                   : 0;
    };
    const std::uint64_t farOnly = finestFor({&far, 1});
    const std::uint64_t nearOnly = finestFor({&near, 1});
    ASSERT_LT(farOnly, nearOnly)
        << "the near view should need full detail where the far one does not";
    const Camera both[] = {far, near};
    EXPECT_GE(finestFor(both), nearOnly);
    EXPECT_TRUE(context->checkNoErrors("multi-view levels of detail").ok());
}

// Views on an orbit around the lattice (as `encore batch` puts its cameras) still get coarser
// levels for what is far from all of them: the levels follow the nearest view, not a bound
// around all the views (which would be nearer than anything inside the orbit).
TEST(LevelOfDetailTest, AnOrbitOfViewsStillDrawsDistantInstancesCoarser) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = lattice();
    const glm::vec3 center = scene.bounds.center();
    const float radius = 1.1f * scene.bounds.radius();
    std::vector<Camera> orbit;
    for (int view = 0; view < 4; ++view) {
        const float angle = glm::half_pi<float>() * float(view);
        const glm::vec3 position =
            center + radius * glm::vec3(std::cos(angle), 0.4f, std::sin(angle));
        orbit.push_back(
            Camera::lookAt(position, center, glm::radians(40.0f), 1.0f, 0.1f, 4.0f * radius));
    }
    auto renderer = renderedViews(*context, scene, orbit, kHeight);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    const GpuCuller& culler = *internals(*renderer).strategy()->report().culler;
    EXPECT_GT(coarserInstances(*context, culler), 0u);
    EXPECT_GT(finestInstances(*context, culler), 0u) << "instances near a view keep full detail";
    EXPECT_TRUE(context->checkNoErrors("orbit levels of detail").ok());
}

}  // namespace
}  // namespace encore::render
