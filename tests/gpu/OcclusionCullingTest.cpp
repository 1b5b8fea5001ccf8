// Two-phase occlusion culling: the depth pyramid keeps the farthest depth of each footprint,
// nothing visible goes missing (every frame of a walk through a grid renders the same pixels as
// the unculled `materials` frame, single- and multisampled, directly and from bundles), hidden
// instances are not drawn, a still camera draws everything in phase 1, the triangle counter
// counts what the draws drew, and bundles are recorded once.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "render/CameraPath.h"
#include "render/culling/GpuCuller.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kWidth = 97;  // Odd sizes exercise the pyramid's last texels.
constexpr std::uint32_t kHeight = 61;

scene::SceneData denseGrid() {
    scene::GeneratorOptions options;
    options.objectCount = 600;
    options.meshCount = 5;
    options.materialCount = 3;
    options.spacing = 2.2f;
    auto glb = scene::generateSceneGlb(options);
    EXPECT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "dense-grid.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// A walk at object height through the grid, looking along it: the nearest objects hide most of
// the rest.
std::vector<Camera> walk(const scene::SceneData& scene, std::size_t frames) {
    const glm::vec3 low = scene.bounds.min;
    const glm::vec3 high = scene.bounds.max;
    const glm::vec3 center = (low + high) * 0.5f;
    std::vector<Camera> cameras;
    for (std::size_t frame = 0; frame < frames; ++frame) {
        const float t = float(frame) / float(frames);
        const glm::vec3 eye{low.x - 2.0f + t * (high.x - low.x) * 0.5f, center.y,
                            center.z + (t - 0.5f) * (high.z - low.z) * 0.3f};
        const glm::vec3 target = eye + glm::vec3(10.0f, -0.2f, 2.0f * (t - 0.5f));
        cameras.push_back(Camera::lookAt(eye, target, glm::radians(60.0f),
                                         float(kWidth) / float(kHeight), 0.05f, 500.0f));
    }
    return cameras;
}

image::ImageRgba8 readImage(Renderer& renderer) {
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

std::uint64_t sum(const std::vector<std::uint32_t>& counts) {
    std::uint64_t total = 0;
    for (std::uint32_t count : counts) {
        total += count;
    }
    return total;
}

// Instances drawn in one phase, summed over draws and levels.
std::uint64_t phaseCount(gpu::Context& context, const GpuCuller& culler, std::uint32_t phase) {
    std::uint64_t total = 0;
    for (const auto& levels : test::culledCountsByLevel(context, culler)) {
        for (const auto& phases : levels) {
            total += phases[phase];
        }
    }
    return total;
}

class OcclusionCullingTest
    : public ::testing::TestWithParam<std::tuple<StrategyKind, std::uint32_t>> {};

TEST_P(OcclusionCullingTest, EveryFrameOfAWalkEqualsTheUnculledFrameAndHidesInstances) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto [kind, samples] = GetParam();
    const auto scene = denseGrid();
    const auto cameras = walk(scene, 6);
    auto unculled = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, samples));
    auto culled = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, samples));
    auto frustumOnly = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, samples));
    ASSERT_TRUE(unculled.ok() && culled.ok() && frustumOnly.ok());
    frustumOnly->setCullingOptions({.occlusion = false, .levelsOfDetail = false});
    ASSERT_TRUE(unculled->prepare(scene, StrategyKind::Materials).ok());
    ASSERT_TRUE(culled->prepare(scene, kind).ok());
    ASSERT_TRUE(frustumOnly->prepare(scene, kind).ok());
    std::uint64_t recorded = 0;
    std::uint64_t hiddenFrames = 0;
    for (std::size_t frame = 0; frame < cameras.size(); ++frame) {
        unculled->renderFrame(cameras[frame]);
        culled->renderFrame(cameras[frame]);
        frustumOnly->renderFrame(cameras[frame]);
        const auto expected = readImage(*unculled);
        const auto image = readImage(*culled);
        EXPECT_EQ(test::differingPixels(expected, image, 0), 0u) << "frame " << frame;
        EXPECT_GT(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.2);
        const std::uint64_t drawn = sum(
            test::culledInstanceCounts(*context, *internals(*culled).strategy()->report().culler));
        const std::uint64_t inFrustum = sum(test::culledInstanceCounts(
            *context, *internals(*frustumOnly).strategy()->report().culler));
        EXPECT_LE(drawn, inFrustum) << "frame " << frame;
        hiddenFrames += 5 * drawn < 4 * inFrustum;
        if (frame == 0) {
            recorded = internals(*culled).strategy()->report().bundlesRecorded;
        }
    }
    EXPECT_GE(hiddenFrames, 3u) << "the nearest objects should hide a fifth of the grid in view";
    EXPECT_EQ(internals(*culled).strategy()->report().bundlesRecorded, recorded);
    EXPECT_TRUE(context->checkNoErrors("occlusion culling").ok());
}

INSTANTIATE_TEST_SUITE_P(DirectAndBundled,
                         OcclusionCullingTest,
                         ::testing::Combine(::testing::Values(StrategyKind::GpuCulling,
                                                              StrategyKind::GpuCullingBundles),
                                            ::testing::Values(1u, 4u)),
                         [](const auto& info) {
                             return test::strategyTestName(std::get<0>(info.param)) + "_" +
                                    std::to_string(std::get<1>(info.param)) + "x";
                         });

// The benchmark scenes: every frame along their camera paths, moving a little each frame as a
// walk would, renders the same pixels with gpu-culling-bundles (occlusion culling on, levels of
// detail off) as with bundles, while occlusion culling draws part of what the frustum holds. The
// large target's pyramid stops before one texel (DepthPyramid's eight levels): the blocks nearest
// the camera, larger than its last texels, are tested against several of them.
struct BenchmarkScene {
    scene::SceneLayout layout;
    std::uint32_t width;
    std::uint32_t height;
};

class BenchmarkSceneOcclusionTest : public ::testing::TestWithParam<BenchmarkScene> {};

TEST_P(BenchmarkSceneOcclusionTest, EveryFrameEqualsBundlesWithFewerTriangles) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    const auto [layout, width, height] = GetParam();
    options.layout = layout;
    options.objectCount = 3000;
    options.tessellation = 4;
    auto glb = scene::generateSceneGlb(options);
    ASSERT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "benchmark-scene.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto path = CameraPath::forLayout(options);
    ASSERT_TRUE(path.has_value());
    auto bundles = Renderer::create(*context, test::pixelTestOptions(width, height));
    auto culled = Renderer::create(*context, test::pixelTestOptions(width, height));
    auto frustumOnly = Renderer::create(*context, test::pixelTestOptions(width, height));
    ASSERT_TRUE(bundles.ok() && culled.ok() && frustumOnly.ok());
    frustumOnly->setCullingOptions({.occlusion = false, .levelsOfDetail = false});
    ASSERT_TRUE(bundles->prepare(*scene, StrategyKind::Bundles).ok());
    ASSERT_TRUE(culled->prepare(*scene, StrategyKind::GpuCullingBundles).ok());
    ASSERT_TRUE(frustumOnly->prepare(*scene, StrategyKind::GpuCullingBundles).ok());
    culled->setTriangleCounting(true);
    frustumOnly->setTriangleCounting(true);
    constexpr int kFrames = 5;
    for (int frame = 0; frame < kFrames; ++frame) {
        const Camera camera =
            path->cameraAtDistance(0.3f * float(frame), float(width) / float(height));
        bundles->renderFrame(camera);
        culled->renderFrame(camera);
        frustumOnly->renderFrame(camera);
        EXPECT_EQ(test::differingPixels(readImage(*bundles), readImage(*culled), 0), 0u)
            << "frame " << frame;
    }
    const auto drawn = culled->takeDrawnTriangles();
    const auto inFrustum = frustumOnly->takeDrawnTriangles();
    ASSERT_TRUE(drawn.ok() && inFrustum.ok());
    ASSERT_EQ(drawn->size(), std::size_t(kFrames));
    // From the third frame: the first draws everything in the frustum in phase 2 (nothing was
    // visible before) and marks it visible, so the second draws it all again in phase 1 and
    // only then learns what its depth hides. The city's nearest blocks hide most of it; the
    // lattice, seen at this size, a sixth or more.
    const double hiddenAtLeast = layout == scene::SceneLayout::City ? 0.5 : 0.1;
    for (int frame = 2; frame < kFrames; ++frame) {
        EXPECT_LT(double((*drawn)[frame]), (1.0 - hiddenAtLeast) * double((*inFrustum)[frame]))
            << "frame " << frame;
    }
    EXPECT_TRUE(context->checkNoErrors("benchmark scene").ok());
}

INSTANTIATE_TEST_SUITE_P(
    FlythroughAndCity,
    BenchmarkSceneOcclusionTest,
    ::testing::Values(BenchmarkScene{scene::SceneLayout::Lattice, kWidth, kHeight},
                      BenchmarkScene{scene::SceneLayout::City, kWidth, kHeight},
                      BenchmarkScene{scene::SceneLayout::City, 1100, 620}),
    [](const auto& info) {
        return std::string(scene::sceneLayoutName(info.param.layout)) + "_" +
               std::to_string(info.param.width);
    });

// A still camera: the first frame finds everything in phase 2 (nothing was visible before), the
// next draws it all in phase 1 and nothing in phase 2. The triangle counter adds up the draws.
TEST(OcclusionCullingPhasesTest, AStillCameraDrawsEverythingInPhaseOneFromTheSecondFrame) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = denseGrid();
    const Camera camera = walk(scene, 6)[2];
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::GpuCullingBundles).ok());
    const GpuCuller& culler = *internals(*renderer).strategy()->report().culler;
    renderer->renderFrame(camera);
    ASSERT_TRUE(renderer->readImage().ok());
    const std::uint64_t first = phaseCount(*context, culler, 1);
    EXPECT_EQ(phaseCount(*context, culler, 0), 0u);
    EXPECT_GT(first, 0u);
    renderer->renderFrame(camera);
    ASSERT_TRUE(renderer->readImage().ok());
    EXPECT_EQ(phaseCount(*context, culler, 0), first);
    EXPECT_EQ(phaseCount(*context, culler, 1), 0u);

    // Every level of every draw adds its triangles per instance drawn.
    auto bytes = gpu::readBuffer(*context, culler.indirectArguments(), 0,
                                 culler.indirectArguments().GetSize());
    ASSERT_TRUE(bytes.ok());
    std::uint64_t expected = 0;
    for (std::size_t draw = 0; draw < culler.draws().size(); ++draw) {
        const CulledDraw& culled = culler.draws()[draw];
        for (std::uint32_t level = 0; level < culled.levelCount(); ++level) {
            std::uint32_t words[5];
            std::memcpy(words, bytes->data() + culler.argumentsOffset(draw, level, 0), 20);
            expected += std::uint64_t(words[0] / 3) * words[1];
        }
    }
    std::uint32_t counted = 0;
    std::memcpy(&counted, bytes->data() + culler.drawnTrianglesOffset(), 4);
    EXPECT_EQ(counted, expected);
    EXPECT_GT(counted, 0u);
    EXPECT_LT(counted, submittedTriangles(culler.draws()));
}

// Level k + 1 holds the farthest of the two by two texels of level k it covers (fewer at an odd
// edge), level 0 the farthest of the depth, drawn or cleared; each level holds
// ceil(size / 2^(k+1)) texels a side, the last one texel.
TEST(DepthPyramidTest, EachTexelHoldsTheFarthestDepthOfItsFootprint) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = denseGrid();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, 4));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::GpuCulling).ok());
    // The second frame's phase 1 draws what the first found visible.
    renderer->renderFrame(walk(scene, 6)[1]);
    renderer->renderFrame(walk(scene, 6)[1]);
    ASSERT_TRUE(renderer->readImage().ok());
    const DepthPyramid& pyramid = internals(*renderer).strategy()->report().culler->depthPyramid();
    ASSERT_TRUE(pyramid.builtFor(renderer->target().depthTexture()));
    const std::uint32_t textureWidth = pyramid.texture().GetWidth();
    std::vector<std::vector<float>> levels;
    for (std::uint32_t level = 0; level < pyramid.levelCount(); ++level) {
        auto values = gpu::readTextureR32Float(*context, pyramid.texture(), level);
        ASSERT_TRUE(values.ok()) << values.error().message;
        levels.push_back(std::move(*values));
    }
    auto texel = [&](std::uint32_t level, std::uint32_t x, std::uint32_t y) {
        return levels[level][y * std::max(textureWidth >> level, 1u) + x];
    };
    ASSERT_EQ(DepthPyramid::levelSize(kWidth, 0), (kWidth + 1) / 2);
    // Small targets reduce to one texel; large ones stop at eight levels (two dispatches).
    ASSERT_EQ(DepthPyramid::levelSize(kWidth, pyramid.levelCount() - 1), 1u);
    ASSERT_EQ(DepthPyramid::levelSize(kHeight, pyramid.levelCount() - 1), 1u);
    ASSERT_GT(DepthPyramid::levelSize(std::max(kWidth, kHeight), pyramid.levelCount() - 2), 1u)
        << "no level past the first of one texel";
    float nearest = 1.0f;
    float farthest = 0.0f;
    for (std::uint32_t y = 0; y < DepthPyramid::levelSize(kHeight, 0); ++y) {
        for (std::uint32_t x = 0; x < DepthPyramid::levelSize(kWidth, 0); ++x) {
            nearest = std::min(nearest, texel(0, x, y));
            farthest = std::max(farthest, texel(0, x, y));
        }
    }
    EXPECT_GE(nearest, 0.0f);
    EXPECT_LT(nearest, 0.999f) << "the walk's nearest objects cover texels";
    EXPECT_EQ(farthest, 1.0f) << "the sky between objects keeps the cleared depth";
    for (std::uint32_t level = 1; level < levels.size(); ++level) {
        const std::uint32_t width = DepthPyramid::levelSize(kWidth, level);
        const std::uint32_t height = DepthPyramid::levelSize(kHeight, level);
        const std::uint32_t finerWidth = DepthPyramid::levelSize(kWidth, level - 1);
        const std::uint32_t finerHeight = DepthPyramid::levelSize(kHeight, level - 1);
        for (std::uint32_t y = 0; y < height; ++y) {
            for (std::uint32_t x = 0; x < width; ++x) {
                float expected = 0.0f;
                for (std::uint32_t fy = 2 * y; fy <= std::min(2 * y + 1, finerHeight - 1); ++fy) {
                    for (std::uint32_t fx = 2 * x; fx <= std::min(2 * x + 1, finerWidth - 1);
                         ++fx) {
                        expected = std::max(expected, texel(level - 1, fx, fy));
                    }
                }
                ASSERT_EQ(texel(level, x, y), expected)
                    << "level " << level << " texel " << x << "," << y;
            }
        }
    }
}

}  // namespace
}  // namespace encore::render
