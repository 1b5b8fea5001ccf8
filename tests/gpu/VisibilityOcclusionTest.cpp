// The visibility strategy's culling (docs/visibility.md): with two-phase occlusion culling and
// levels of detail on, fly-through and city frames look as gpu-culling-bundles draws them with the
// same options and as the visibility strategy draws them without occlusion (nothing visible goes
// missing); a wall, drawn in compute or by the hardware, hides the objects behind it, which stop
// being rasterised (the triangle counts add both phases); an object that
// comes out from behind the wall when the camera moves is drawn in that very frame; and levels of
// detail list exactly the triangles GPU culling draws, in frames of one view and of several.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "VisibilityTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "image/ImageCompare.h"
#include "render/renderer/RendererCore.h"
#include "render/visibility/VisibilityStrategy.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kWidth = 128;
constexpr std::uint32_t kHeight = 96;

std::unique_ptr<Renderer> renderer(gpu::Context& context,
                                   const scene::SceneData& scene,
                                   StrategyKind kind,
                                   CullingOptions culling) {
    auto created = Renderer::create(context, test::pixelTestOptions(kWidth, kHeight));
    EXPECT_TRUE(created.ok());
    if (!created.ok()) {
        return nullptr;
    }
    auto result = std::make_unique<Renderer>(std::move(*created));
    result->setCullingOptions(culling);
    auto prepared = result->prepare(scene, kind);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    return result;
}

image::ImageRgba8 frame(Renderer& renderer, const Camera& camera) {
    renderer.renderFrame(camera);
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

const VisibilityStrategy& visibilityOf(const Renderer& renderer) {
    const auto* strategy = dynamic_cast<const VisibilityStrategy*>(internals(renderer).strategy());
    EXPECT_NE(strategy, nullptr);
    return *strategy;
}

// The triangles the last frame's cull listed (the chosen levels of the items it kept).
std::uint32_t listedTriangles(gpu::Context& context, const Renderer& renderer) {
    return test::readWord(context, visibilityOf(renderer).counters(),
                          VisibilityStrategy::kListedTrianglesOffset);
}

// Frames of a walk at object height through the scene, looking along it.
std::vector<Camera> walk(const scene::SceneData& scene, std::size_t frames) {
    const glm::vec3 low = scene.bounds.min;
    const glm::vec3 high = scene.bounds.max;
    const glm::vec3 center = (low + high) * 0.5f;
    const float aspect = float(kWidth) / float(kHeight);
    std::vector<Camera> cameras;
    for (std::size_t i = 0; i < frames; ++i) {
        const float t = 0.2f + 0.4f * float(i) / float(frames);
        const glm::vec3 eye{low.x - 1.0f + t * (high.x - low.x), center.y + 0.3f, center.z};
        cameras.push_back(Camera::lookAt(eye, eye + glm::vec3(10.0f, -1.0f, 3.0f - 1.5f * float(i)),
                                         glm::radians(60.0f), aspect, 0.05f, 500.0f));
    }
    return cameras;
}

class VisibilityOcclusionTest : public ::testing::TestWithParam<scene::SceneLayout> {};

TEST_P(VisibilityOcclusionTest, WalkLooksLikeGpuCullingAndMissesNothing) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = test::generatedVisibilityScene(GetParam(), 300);
    const CullingOptions culled{.occlusion = true, .levelsOfDetail = true};
    const CullingOptions sameLevelsUnoccluded{.occlusion = false, .levelsOfDetail = true};
    const CullingOptions frustumOnly{.occlusion = false, .levelsOfDetail = false};
    auto reference = renderer(*context, scene, StrategyKind::GpuCullingBundles, culled);
    auto visibility = renderer(*context, scene, StrategyKind::Visibility, culled);
    auto unoccluded = renderer(*context, scene, StrategyKind::Visibility, sameLevelsUnoccluded);
    auto full = renderer(*context, scene, StrategyKind::Visibility, frustumOnly);
    ASSERT_TRUE(reference && visibility && unoccluded && full);
    std::uint64_t listed = 0;
    std::uint64_t listedUnoccluded = 0;
    std::uint64_t listedFull = 0;
    const auto cameras = walk(scene, 5);
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        SCOPED_TRACE("frame " + std::to_string(i));
        const auto expected = frame(*reference, cameras[i]);
        const auto image = frame(*visibility, cameras[i]);
        EXPECT_TRUE(visibilityOf(*visibility).lastFrameOccluded());
        test::expectVisibilityClose(expected, image);
        // The same levels without occlusion culling: the same pixels, so nothing visible was
        // culled (ties in depth between two items may resolve either way: a few pixels).
        const auto everything = frame(*unoccluded, cameras[i]);
        EXPECT_LE(test::differingPixels(everything, image, 2), 3u);
        EXPECT_GT(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.05);
        frame(*full, cameras[i]);
        listed += listedTriangles(*context, *visibility);
        listedUnoccluded += listedTriangles(*context, *unoccluded);
        listedFull += listedTriangles(*context, *full);
    }
    // Occlusion culling leaves fewer triangles than the same levels in the whole frustum, and
    // those fewer than full detail.
    EXPECT_LT(listed, listedUnoccluded);
    EXPECT_LT(listedUnoccluded, listedFull);
    std::printf(
        "listed triangles over the walk: %llu with occlusion and levels of detail, %llu "
        "without occlusion, %llu at full detail\n",
        (unsigned long long)listed, (unsigned long long)listedUnoccluded,
        (unsigned long long)listedFull);
    EXPECT_TRUE(context->checkNoErrors("visibility occlusion culling").ok());
}

INSTANTIATE_TEST_SUITE_P(Layouts,
                         VisibilityOcclusionTest,
                         ::testing::Values(scene::SceneLayout::Lattice, scene::SceneLayout::City),
                         [](const auto& info) {
                             return info.param == scene::SceneLayout::Lattice
                                        ? std::string("flythrough")
                                        : std::string("city");
                         });

constexpr std::uint32_t kGridQuads = 10;  // Each hidden object: 200 triangles.
constexpr std::uint32_t kObjectTriangles = kGridQuads * kGridQuads * 2;
constexpr std::uint32_t kObjects = 16;

// A wall (one quad, 4 x 3 units at z = 0, facing +z) and a 4 x 4 block of small tessellated
// squares behind it at z = -1.5, x and y in [-1.8, 1.8]: the front camera (at z = 3) sees none of
// them; from x = 3.5 the column at x = 1.5 comes out from behind the wall's edge.
scene::SceneData wallScene() {
    test::GltfBuilder builder;
    const auto wallPositions = builder.addPositions(
        {{-2.0f, -1.5f, 0.0f}, {2.0f, -1.5f, 0.0f}, {2.0f, 1.5f, 0.0f}, {-2.0f, 1.5f, 0.0f}});
    const auto wallIndices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
    const auto wallMaterial = builder.addMaterial({.baseColor = {0.8f, 0.8f, 0.8f, 1.0f}});
    std::vector<glm::vec3> positions;
    std::vector<std::uint16_t> indices;
    const float size = 0.6f;
    for (std::uint32_t y = 0; y <= kGridQuads; ++y) {
        for (std::uint32_t x = 0; x <= kGridQuads; ++x) {
            positions.push_back({size * (float(x) / kGridQuads - 0.5f),
                                 size * (float(y) / kGridQuads - 0.5f), 0.0f});
        }
    }
    for (std::uint32_t y = 0; y < kGridQuads; ++y) {
        for (std::uint32_t x = 0; x < kGridQuads; ++x) {
            const auto corner = std::uint16_t(y * (kGridQuads + 1) + x);
            const auto above = std::uint16_t(corner + kGridQuads + 1);
            indices.insert(indices.end(),
                           {corner, std::uint16_t(corner + 1), std::uint16_t(above + 1), corner,
                            std::uint16_t(above + 1), above});
        }
    }
    const auto objectMaterial = builder.addMaterial({.baseColor = {0.9f, 0.2f, 0.1f, 1.0f}});
    const auto object =
        builder.addMesh({.attributes = {{"POSITION", builder.addPositions(positions)}},
                         .indices = builder.addIndices(indices),
                         .material = objectMaterial});
    std::vector<std::uint32_t> nodes = {
        builder.addNode({.mesh = builder.addMesh({.attributes = {{"POSITION", wallPositions}},
                                                  .indices = wallIndices,
                                                  .material = wallMaterial})})};
    for (std::uint32_t i = 0; i < kObjects; ++i) {
        const glm::vec3 at{-1.5f + float(i % 4), -1.2f + 0.8f * float(i / 4), -1.5f};
        nodes.push_back(builder.addNode({.mesh = object, .translation = at}));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "wall.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

const float kAspect = float(kWidth) / float(kHeight);

// The triangles the last frame rasterised: in compute, then in hardware.
std::array<std::uint32_t, 2> rasteriserCounts(gpu::Context& context, const Renderer& renderer) {
    const VisibilityStrategy& strategy = visibilityOf(renderer);
    const std::uint64_t offset = strategy.rasterCountsOffset(0);
    return {test::readWord(context, strategy.rasterCounts(), offset),
            test::readWord(context, strategy.rasterCounts(), offset + 4)};
}

// The wall drawn by a compute workgroup (64 x 48 pixels) or, without workgroups, by the hardware:
// either way it is in the pyramid that phase 2 tests the objects against.
class VisibilityWallTest : public ::testing::TestWithParam<float> {};

TEST_P(VisibilityWallTest, HiddenObjectsAreNotRasterised) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = wallScene();
    const float workgroupPixels = GetParam();
    const bool wallInHardware = workgroupPixels == 0.0f;
    CullingOptions culling{.occlusion = true, .levelsOfDetail = false};
    culling.workgroupRasterPixels = workgroupPixels;
    auto occluded = renderer(*context, scene, StrategyKind::Visibility, culling);
    culling.occlusion = false;
    auto frustumOnly = renderer(*context, scene, StrategyKind::Visibility, culling);
    ASSERT_TRUE(occluded && frustumOnly);
    const Camera front = test::frontCamera(kAspect);
    const auto everything = frame(*frustumOnly, front);
    EXPECT_EQ(listedTriangles(*context, *frustumOnly), 2 + kObjects * kObjectTriangles);
    const auto all = rasteriserCounts(*context, *frustumOnly);
    EXPECT_GT(all[0], kObjects * kObjectTriangles / 2);
    EXPECT_EQ(all[1], wallInHardware ? 2u : 0u);
    const std::array<std::uint32_t, 2> wallOnly =
        wallInHardware ? std::array<std::uint32_t, 2>{0, 2} : std::array<std::uint32_t, 2>{2, 0};
    // The first frame knows nothing of the last: its second phase tests everything against an
    // empty pyramid. The second draws all that in phase 1 and finds the objects hidden; from the
    // third on, phase 1 draws the wall and phase 2 rejects the objects. The counts add both
    // phases.
    for (int i = 0; i < 4; ++i) {
        SCOPED_TRACE("frame " + std::to_string(i));
        const auto image = frame(*occluded, front);
        EXPECT_EQ(test::differingPixels(everything, image, 0), 0u);
        if (i < 2) {
            EXPECT_EQ(rasteriserCounts(*context, *occluded), all);
        } else {
            EXPECT_EQ(listedTriangles(*context, *occluded), 2u);
            EXPECT_EQ(rasteriserCounts(*context, *occluded), wallOnly);
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility wall").ok());
}

INSTANTIATE_TEST_SUITE_P(WallRasteriser,
                         VisibilityWallTest,
                         ::testing::Values(VisibilityStrategy::kMaxWorkgroupPixels, 0.0f),
                         [](const auto& info) {
                             return info.param == 0.0f ? std::string("hardware")
                                                       : std::string("workgroup");
                         });

TEST(VisibilityDisocclusionTest, AnObjectComingOutFromBehindTheWallAppearsInThatFrame) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = wallScene();
    const Camera front = test::frontCamera(kAspect);
    const Camera aside = test::frontCamera(kAspect, 3.5f);
    auto occluded = renderer(*context, scene, StrategyKind::Visibility,
                             {.occlusion = true, .levelsOfDetail = false});
    ASSERT_TRUE(occluded);
    for (int i = 0; i < 3; ++i) {
        frame(*occluded, front);
    }
    ASSERT_EQ(listedTriangles(*context, *occluded), 2u);
    const auto image = frame(*occluded, aside);
    // Phase 1 drew the wall; phase 2 found the column at x = 1.5 visible past its edge.
    EXPECT_GE(listedTriangles(*context, *occluded), 2 + 4 * kObjectTriangles);
    auto unculled = renderer(*context, scene, StrategyKind::Visibility,
                             {.occlusion = false, .levelsOfDetail = false});
    auto reference = renderer(*context, scene, StrategyKind::GpuCullingBundles,
                              {.occlusion = false, .levelsOfDetail = false});
    ASSERT_TRUE(unculled && reference);
    const auto everything = frame(*unculled, aside);
    EXPECT_EQ(test::differingPixels(everything, image, 0), 0u);
    const auto expected = frame(*reference, aside);
    EXPECT_EQ(test::differingPixels(expected, image, 2), 0u);
    // The objects' red shows beside the wall.
    std::size_t red = 0;
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const std::uint8_t* pixel = image.pixel(x, y);
            red += pixel[0] > pixel[1] + 60;  // Orange-red, not the grey wall.
        }
    }
    EXPECT_GT(red, 20u);
    EXPECT_TRUE(context->checkNoErrors("visibility disocclusion").ok());
}

// Frames of one view test items against the frustum by world spheres, computed once the
// transforms hold still: an instance moved from behind the camera to just in front of it shows
// in that frame (tested by its matrix) and in the frames after (the spheres computed again), one
// moved far away goes, each frame as GPU culling draws it.
TEST(VisibilityWorldSpheresTest, MovedInstancesAreCulledWhereTheyAreNow) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = test::generatedVisibilityScene(scene::SceneLayout::Grid, 200);
    const Camera camera = walk(scene, 1)[0];
    const CullingOptions culling{.occlusion = true, .levelsOfDetail = false};
    auto visibility = renderer(*context, scene, StrategyKind::Visibility, culling);
    auto reference = renderer(*context, scene, StrategyKind::GpuCullingBundles, culling);
    ASSERT_TRUE(visibility && reference);
    auto compare = [&](const char* what) {
        SCOPED_TRACE(what);
        const auto expected = frame(*reference, camera);
        const auto image = frame(*visibility, camera);
        test::expectVisibilityClose(expected, image);
        return image;
    };
    compare("first frame");
    const auto still = compare("spheres in use");
    // The instance farthest behind the camera, and the one nearest in front of it.
    const glm::vec3 eye = camera.position;
    const glm::vec3 forward =
        -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    std::size_t behind = 0;
    std::size_t nearest = 0;
    float behindDepth = 0.0f;
    float nearestDepth = 3.4e38f;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const float depth = glm::dot(glm::vec3(scene.instances[i].world[3]) - eye, forward);
        if (depth < behindDepth) {
            behindDepth = depth;
            behind = i;
        }
        if (depth > 0.5f && depth < nearestDepth) {
            nearestDepth = depth;
            nearest = i;
        }
    }
    ASSERT_LT(behindDepth, -1.0f) << "the walk's camera should leave instances behind it";
    const glm::mat4 inFront = glm::translate(glm::mat4(1.0f), eye + forward * 1.5f);
    const glm::mat4 farAway = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1000.0f, 0.0f));
    for (Renderer* moved : {visibility.get(), reference.get()}) {
        ASSERT_TRUE(moved->updateInstance(behind, inFront).ok());
        ASSERT_TRUE(moved->updateInstance(nearest, farAway).ok());
    }
    const auto after = compare("the frame of the move");
    EXPECT_GT(test::differingPixels(still, after, 2), std::size_t(kWidth * kHeight / 20))
        << "the instance moved in front of the camera should cover much of the view";
    compare("spheres computed again");
    compare("spheres in use again");
    EXPECT_TRUE(context->checkNoErrors("visibility world spheres").ok());
}

// With everything in view (the scene framed) and occlusion off, the cull lists exactly the
// triangles GPU culling draws: the same level for every instance.
TEST(VisibilityLevelsTest, LevelsListTheTrianglesGpuCullingDraws) {
    ENCORE_REQUIRE_VULKAN(context);
    for (auto layout : {scene::SceneLayout::Grid, scene::SceneLayout::Lattice}) {
        SCOPED_TRACE(layout == scene::SceneLayout::Grid ? "grid" : "lattice");
        const auto scene = test::generatedVisibilityScene(layout, 200);
        const Camera framed = Camera::framing(scene.bounds, kAspect);
        const CullingOptions levels{.occlusion = false, .levelsOfDetail = true};
        const CullingOptions fullDetail{.occlusion = false, .levelsOfDetail = false};
        auto reference = renderer(*context, scene, StrategyKind::GpuCullingBundles, levels);
        auto visibility = renderer(*context, scene, StrategyKind::Visibility, levels);
        auto full = renderer(*context, scene, StrategyKind::Visibility, fullDetail);
        ASSERT_TRUE(reference && visibility && full);
        for (float lodError : {1.0f, 4.0f}) {
            CullingOptions options = levels;
            options.lodErrorPixels = lodError;
            reference->setCullingOptions(options);
            visibility->setCullingOptions(options);
            const auto expected = frame(*reference, framed);
            const auto image = frame(*visibility, framed);
            test::expectVisibilityClose(expected, image);
            const auto counts = internals(*reference).strategy()->report().gpuTriangleCounts;
            ASSERT_TRUE(counts.has_value());
            const std::uint32_t drawn =
                test::readWord(*context, counts->buffer, counts->hardwareOffset);
            EXPECT_EQ(listedTriangles(*context, *visibility), drawn) << "error " << lodError;
            frame(*full, framed);
            EXPECT_LT(drawn, listedTriangles(*context, *full)) << "no coarser level chosen";
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility levels").ok());
}

// A multi-view frame: as GPU culling, no occlusion culling (each view frames the scene) and one
// level per item for all views, chosen for the nearest; the pictures match.
TEST(VisibilityLevelsTest, MultiViewFramesChooseLevelsAsGpuCulling) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = test::generatedVisibilityScene(scene::SceneLayout::Grid, 200);
    const glm::vec3 center = scene.bounds.center();
    const float radius = scene.bounds.radius();
    const float aspect = float(kWidth / 4) / float(kHeight);
    std::vector<Camera> cameras;
    for (int view = 0; view < 4; ++view) {
        const float angle = glm::radians(30.0f + 80.0f * float(view));
        const float distance = radius * (1.2f + 0.6f * float(view));
        const glm::vec3 eye = center + distance * glm::vec3(std::cos(angle), 0.5f, std::sin(angle));
        cameras.push_back(
            Camera::lookAt(eye, center, glm::radians(60.0f), aspect, 0.05f, 4.0f * distance));
    }
    const CullingOptions culling{.occlusion = true, .levelsOfDetail = true};
    auto reference = renderer(*context, scene, StrategyKind::GpuCullingBundles, culling);
    auto visibility = renderer(*context, scene, StrategyKind::Visibility, culling);
    ASSERT_TRUE(reference && visibility);
    for (int i = 0; i < 2; ++i) {
        reference->renderViews(cameras);
        visibility->renderViews(cameras);
    }
    auto expected = reference->readImage();
    auto image = visibility->readImage();
    ASSERT_TRUE(expected.ok() && image.ok());
    test::expectVisibilityClose(*expected, *image);
    EXPECT_FALSE(visibilityOf(*visibility).lastFrameOccluded());
    EXPECT_EQ(visibilityOf(*visibility).lastViewCount(), 4u);
    // The counters hold the last view's cull, which lists what GPU culling's one cull draws.
    const auto counts = internals(*reference).strategy()->report().gpuTriangleCounts;
    ASSERT_TRUE(counts.has_value());
    const std::uint32_t listed = listedTriangles(*context, *visibility);
    EXPECT_EQ(listed, test::readWord(*context, counts->buffer, counts->hardwareOffset));
    EXPECT_LT(listed, visibilityOf(*visibility).tables().triangleCount) << "all at level 0";
    EXPECT_TRUE(context->checkNoErrors("visibility multi-view levels").ok());
}

}  // namespace
}  // namespace encore::render
