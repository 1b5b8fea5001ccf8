// The visibility strategy's clusters (docs/visibility.md): each cluster of a listed item is
// culled on its own, against the frustum, by its cone of normals and, in the second occlusion
// phase, against the depth pyramid. A densely tessellated sphere seen whole, half outside the
// view, mirrored, double-sided, orthographic, and coming out from behind a wall: the raster
// passes set up clearly fewer triangles than with cluster culling off (and, behind the wall,
// rasterise fewer), and the picture is the same pixel for pixel.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

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

namespace encore::render {
namespace {

constexpr std::uint32_t kWidth = 128;
constexpr std::uint32_t kHeight = 96;
constexpr float kAspect = float(kWidth) / float(kHeight);
constexpr std::uint32_t kRings = 96;
constexpr std::uint32_t kSegments = 128;
constexpr std::uint32_t kSphereTriangles = kRings * kSegments * 2;

struct SphereScene {
    bool mirrored = false;
    bool doubleSided = false;
    bool wall = false;  // A wall at z = 0 in front of the sphere, which sits at z = -2.
};

// A unit sphere of kSphereTriangles triangles (counter-clockwise seen from outside), at the
// origin or behind a wall; mirrored: scaled by -1 along x (a negative determinant).
scene::SceneData sphereScene(const SphereScene& options) {
    test::GltfBuilder builder;
    std::vector<glm::vec3> positions;
    for (std::uint32_t r = 0; r <= kRings; ++r) {
        for (std::uint32_t s = 0; s <= kSegments; ++s) {
            const float theta = 3.14159265f * float(r) / float(kRings);
            const float phi = 6.2831853f * float(s) / float(kSegments);
            positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                 std::sin(theta) * std::sin(phi)});
        }
    }
    std::vector<std::uint32_t> indices;
    const std::uint32_t row = kSegments + 1;
    for (std::uint32_t r = 0; r < kRings; ++r) {
        for (std::uint32_t s = 0; s < kSegments; ++s) {
            const std::uint32_t a = r * row + s, b = a + row;
            indices.insert(indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    }
    const auto material = builder.addMaterial(
        {.baseColor = {0.9f, 0.5f, 0.2f, 1.0f}, .doubleSided = options.doubleSided});
    const auto sphere =
        builder.addMesh({.attributes = {{"POSITION", builder.addPositions(positions)},
                                        {"NORMAL", builder.addNormals(positions)}},
                         .indices = builder.addIndices(indices),
                         .material = material});
    test::GltfBuilder::NodeDesc node{.mesh = sphere};
    if (options.mirrored) {
        node.scale = glm::vec3(-1.0f, 1.0f, 1.0f);
    }
    if (options.wall) {
        node.translation = glm::vec3(0.0f, 0.0f, -2.0f);
    }
    std::vector<std::uint32_t> nodes = {builder.addNode(node)};
    if (options.wall) {
        const auto wall = builder.addMesh(
            {.attributes = {{"POSITION", builder.addPositions({{-2.0f, -2.0f, 0.0f},
                                                               {2.0f, -2.0f, 0.0f},
                                                               {2.0f, 2.0f, 0.0f},
                                                               {-2.0f, 2.0f, 0.0f}})}},
             .indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3}),
             .material = builder.addMaterial({.baseColor = {0.7f, 0.7f, 0.7f, 1.0f}})});
        nodes.push_back(builder.addNode({.mesh = wall}));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "sphere.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

std::unique_ptr<Renderer> renderer(gpu::Context& context,
                                   const scene::SceneData& scene,
                                   bool clusterCulling,
                                   bool occlusion = false) {
    auto created =
        Renderer::create(context, test::pixelTestOptions(kWidth, kHeight, 1, DebugChannel::Shaded));
    EXPECT_TRUE(created.ok());
    if (!created.ok()) {
        return nullptr;
    }
    auto result = std::make_unique<Renderer>(std::move(*created));
    CullingOptions culling{.occlusion = occlusion, .levelsOfDetail = false};
    culling.clusterCulling = clusterCulling;
    result->setCullingOptions(culling);
    auto prepared = result->prepare(scene, StrategyKind::Visibility);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    return result;
}

// What the last frame did: triangles listed, taken by the rasterisers (compute and hardware:
// front-facing, in the view, not degenerate) and in culled clusters. The raster passes fetch
// and set up the listed triangles less the culled ones.
struct Work {
    std::uint32_t listed = 0;
    std::uint32_t rasterised = 0;
    std::uint32_t culled = 0;

    std::uint32_t setUp() const { return listed - culled; }
};

struct Frame {
    image::ImageRgba8 image;
    Work work;
};

Frame render(gpu::Context& context, Renderer& renderer, const Camera& camera) {
    renderer.renderFrame(camera);
    Frame frame;
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    if (image.ok()) {
        frame.image = std::move(*image);
    }
    const auto* strategy = dynamic_cast<const VisibilityStrategy*>(internals(renderer).strategy());
    EXPECT_NE(strategy, nullptr);
    if (strategy) {
        frame.work.listed = test::readWord(context, strategy->counters(),
                                           VisibilityStrategy::kListedTrianglesOffset);
        frame.work.culled = test::readWord(context, strategy->counters(),
                                           VisibilityStrategy::kCulledTrianglesOffset);
        const std::uint64_t counts = strategy->rasterCountsOffset(0);
        frame.work.rasterised = test::readWord(context, strategy->rasterCounts(), counts) +
                                test::readWord(context, strategy->rasterCounts(), counts + 4);
    }
    return frame;
}

std::size_t coloured(const image::ImageRgba8& image) {
    std::size_t count = 0;
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const std::uint8_t* pixel = image.pixel(x, y);
            count += pixel[0] > pixel[2] + 40;  // The sphere's orange.
        }
    }
    return count;
}

struct Case {
    const char* name;
    SphereScene scene;
    float cameraX;  // 0: the sphere in the middle; 4: its centre on the left edge.
    // At most this fraction of the listed triangles is fetched and set up.
    double maxFraction;
    bool orthographic = false;  // 1.6 units high, from z = 3 along -z.
};

Camera caseCamera(const Case& c) {
    if (!c.orthographic) {
        return test::frontCamera(kAspect, c.cameraX);
    }
    const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(c.cameraX, 0.0f, 3.0f));
    return Camera::orthographic(world, 1.6f * kAspect, 1.6f, 0.1f, 10.0f);
}

class VisibilityClusterTest : public ::testing::TestWithParam<Case> {};

TEST_P(VisibilityClusterTest, CullsClustersAndDrawsTheSamePicture) {
    ENCORE_REQUIRE_VULKAN(context);
    const Case& c = GetParam();
    const auto scene = sphereScene(c.scene);
    ASSERT_FALSE(scene.meshes.empty());
    ASSERT_GT(scene.meshes[0].primitives[0].clusters.size(), kSphereTriangles / 256);
    auto culled = renderer(*context, scene, true);
    auto unculled = renderer(*context, scene, false);
    ASSERT_TRUE(culled && unculled);
    const Camera camera = caseCamera(c);
    const Frame with = render(*context, *culled, camera);
    const Frame without = render(*context, *unculled, camera);
    EXPECT_EQ(test::differingPixels(without.image, with.image, 0), 0u);
    EXPECT_GT(coloured(with.image), 500u);
    EXPECT_EQ(with.work.listed, kSphereTriangles);
    EXPECT_EQ(without.work.listed, kSphereTriangles);
    EXPECT_EQ(without.work.culled, 0u);
    // The culled clusters held only triangles facing away or outside the view, which the
    // rasterisers would have set up and dropped.
    EXPECT_EQ(with.work.rasterised, without.work.rasterised);
    EXPECT_LE(double(with.work.setUp()), double(with.work.listed) * c.maxFraction);
    if (c.scene.doubleSided && c.cameraX == 0.0f) {
        EXPECT_EQ(with.work.culled, 0u) << "a double-sided cluster culled by facing";
    }
    std::printf("%s: %u of %u listed triangles set up with cluster culling, %u rasterised\n",
                c.name, with.work.setUp(), with.work.listed, with.work.rasterised);
    EXPECT_TRUE(context->checkNoErrors("visibility clusters").ok());
}

INSTANTIATE_TEST_SUITE_P(
    Spheres,
    VisibilityClusterTest,
    ::testing::Values(
        Case{"facing", {}, 0.0f, 0.6},
        Case{"half outside", {}, 4.0f, 0.5},
        Case{"mirrored", {.mirrored = true}, 0.0f, 0.6},
        Case{"mirrored half outside", {.mirrored = true}, 4.0f, 0.5},
        Case{"double-sided", {.doubleSided = true}, 0.0f, 1.0},
        Case{"double-sided half outside", {.doubleSided = true}, 4.0f, 0.75},
        Case{"orthographic", {}, 0.0f, 0.7, true},
        Case{"orthographic mirrored half outside", {.mirrored = true}, 2.1f, 0.5, true}),
    [](const auto& info) {
        std::string name = info.param.name;
        for (char& ch : name) {
            ch = (ch == ' ' || ch == '-') ? '_' : ch;
        }
        return name;
    });

// The sphere behind a wall, then seen past its edge: the frame in which it comes out lists it
// in the second phase, whose clusters still behind the wall the pyramid culls; in the frames
// after it, phase 1 takes the clusters visible before and phase 2 culls the others.
TEST(VisibilityClusterOcclusionTest, ClustersBehindTheWallAreNotRasterised) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = sphereScene({.wall = true});
    auto culled = renderer(*context, scene, true, true);
    auto unculled = renderer(*context, scene, false, true);
    ASSERT_TRUE(culled && unculled);
    const Camera hidden = test::frontCamera(kAspect);
    // From x = 5 the wall's edge (x = 2) hides about half of the sphere's side facing the
    // camera: the clusters of the other half show.
    const Camera aside = Camera::lookAt({5.0f, 0.0f, 3.0f}, {0.0f, 0.0f, -2.0f},
                                        glm::half_pi<float>(), kAspect, 0.1f, 20.0f);
    for (int i = 0; i < 2; ++i) {
        render(*context, *culled, hidden);
        render(*context, *unculled, hidden);
    }
    // The frame it comes out in (phase 2 lists it and tests its clusters against the pyramid),
    // then frames that draw in phase 1 the clusters visible in the frame before and test the
    // others in phase 2.
    std::vector<std::uint32_t> rasterisedWithout;
    for (int i = 0; i < 3; ++i) {
        SCOPED_TRACE("frame " + std::to_string(i) + " aside");
        const Frame with = render(*context, *culled, aside);
        const Frame without = render(*context, *unculled, aside);
        EXPECT_EQ(test::differingPixels(without.image, with.image, 0), 0u);
        EXPECT_GT(coloured(with.image), 50u);
        EXPECT_EQ(with.work.listed, without.work.listed);
        EXPECT_GE(with.work.listed, kSphereTriangles);
        rasterisedWithout.push_back(without.work.rasterised);
        if (i == 0) {
            // Listed by phase 2, whose raster drops each triangle the pyramid hides, with
            // cluster culling or without (below: fewer than phase 1 draws without it).
            EXPECT_LE(with.work.rasterised, without.work.rasterised);
        } else {
            // Hidden clusters facing the camera are no longer rasterised by phase 1 either.
            EXPECT_LT(double(with.work.rasterised), double(without.work.rasterised) * 0.85);
        }
        EXPECT_LT(double(with.work.setUp()), double(with.work.listed) * 0.45);
        std::printf(
            "behind the wall, frame %d aside: %u of %u listed triangles set up, %u "
            "rasterised with cluster culling, %u without\n",
            i, with.work.setUp(), with.work.listed, with.work.rasterised, without.work.rasterised);
    }
    EXPECT_LT(double(rasterisedWithout[0]), double(rasterisedWithout[1]) * 0.85);
    EXPECT_TRUE(context->checkNoErrors("visibility cluster occlusion").ok());
}

}  // namespace
}  // namespace encore::render
