// The visibility buffer's depth is the hardware's: the same frames drawn with every triangle
// through the hardware path (whose fragments write the rasteriser's own depth) and with the
// compute rasterisers cover the same pixels, at depths within 1e-6 of each other (issue 28; the
// compute raster interpolates depth on the plane of the unsnapped vertices, as the hardware
// does: on the snapped ones a third of the pixels of these frames were further apart, up to
// 3.3e-4).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "VisibilityTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "render/renderer/RendererCore.h"
#include "render/visibility/VisibilityStrategy.h"
#include "render/visibility/VisibilityTables.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kWidth = 128;
constexpr std::uint32_t kHeight = 96;

// The visibility buffer after drawing `camera`, with the compute rasterisers up to `pixels`
// (0: every triangle through the hardware), and how many triangles each path drew.
struct Drawn {
    std::vector<std::uint8_t> entries;
    std::uint32_t inCompute = 0;
    std::uint32_t inHardware = 0;
};

Drawn draw(gpu::Context& context,
           const scene::SceneData& scene,
           const Camera& camera,
           float pixels) {
    auto renderer = Renderer::create(context, test::pixelTestOptions(kWidth, kHeight, 1));
    EXPECT_TRUE(renderer.ok());
    if (!renderer.ok()) {
        return {};
    }
    CullingOptions culling{.occlusion = false, .levelsOfDetail = false};
    culling.computeRasterPixels = std::min(pixels, VisibilityStrategy::kDefaultComputePixels);
    culling.workgroupRasterPixels = pixels;
    renderer->setCullingOptions(culling);
    EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
    renderer->renderFrame(camera);
    const auto* strategy = dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
    Drawn drawn;
    auto entries = gpu::readBuffer(context, strategy->visibilityBuffer(), 0,
                                   std::uint64_t(kWidth) * kHeight * 8);
    auto counts =
        gpu::readBuffer(context, strategy->rasterCounts(), strategy->rasterCountsOffset(0), 8);
    EXPECT_TRUE(entries.ok() && counts.ok());
    if (entries.ok() && counts.ok()) {
        drawn.entries = std::move(*entries);
        std::memcpy(&drawn.inCompute, counts->data(), 4);
        std::memcpy(&drawn.inHardware, counts->data() + 4, 4);
    }
    return drawn;
}

float depthOf(const std::vector<std::uint8_t>& entries, std::size_t pixel) {
    std::uint32_t high = 0;
    std::memcpy(&high, entries.data() + pixel * 8 + 4, 4);
    return std::bit_cast<float>(~high);
}

bool covered(const std::vector<std::uint8_t>& entries, std::size_t pixel) {
    std::uint32_t high = 0;
    std::memcpy(&high, entries.data() + pixel * 8 + 4, 4);
    return high != 0;
}

TEST(VisibilityDepthTest, ComputeDepthIsTheHardwareDepth) {
    ENCORE_REQUIRE_VULKAN(context);
    const float aspect = float(kWidth) / float(kHeight);
    for (const scene::SceneLayout layout :
         {scene::SceneLayout::Grid, scene::SceneLayout::Lattice}) {
        SCOPED_TRACE(std::string(scene::sceneLayoutName(layout)));
        const auto scene = test::generatedVisibilityScene(layout, 300);
        const glm::vec3 low = scene.bounds.min;
        const glm::vec3 high = scene.bounds.max;
        const glm::vec3 center = (low + high) * 0.5f;
        // Framed, and a frame of a walk at object height (the fly-through's).
        const glm::vec3 eye{low.x - 1.0f + 0.4f * (high.x - low.x), center.y + 0.3f, center.z};
        for (const Camera& camera : {Camera::framing(scene.bounds, aspect),
                                     Camera::lookAt(eye, eye + glm::vec3(10.0f, -1.0f, 3.0f),
                                                    glm::radians(60.0f), aspect, 0.05f, 500.0f)}) {
            const Drawn hardware = draw(*context, scene, camera, 0.0f);
            const Drawn compute =
                draw(*context, scene, camera, VisibilityStrategy::kMaxWorkgroupPixels);
            ASSERT_EQ(hardware.entries.size(), compute.entries.size());
            EXPECT_EQ(hardware.inCompute, 0u);
            EXPECT_GT(compute.inCompute, 10 * compute.inHardware);
            std::size_t both = 0;
            std::size_t coverageDiffers = 0;
            float largest = 0.0f;
            std::size_t beyond = 0;  // Pixels more than 1e-6 apart.
            for (std::size_t pixel = 0; pixel < std::size_t(kWidth) * kHeight; ++pixel) {
                const bool inHardware = covered(hardware.entries, pixel);
                const bool inCompute = covered(compute.entries, pixel);
                coverageDiffers += inHardware != inCompute;
                if (inHardware && inCompute) {
                    ++both;
                    const float d = std::abs(depthOf(hardware.entries, pixel) -
                                             depthOf(compute.entries, pixel));
                    largest = std::max(largest, d);
                    beyond += d > 1e-6f;
                }
            }
            EXPECT_EQ(coverageDiffers, 0u);
            EXPECT_GT(both, std::size_t(kWidth) * kHeight / 10);
            // Within 1e-6, as the issue asks, but for rounding: lavapipe evaluates its depth plane
            // in another order (measured: 1 pixel of the 18,345 of these frames at 1.01e-6).
            EXPECT_LE(beyond, both / 1000) << "largest difference " << largest;
            EXPECT_LE(largest, 2e-6f);
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility depth").ok());
}

// Two copies of one triangle tie in depth at every pixel, and the visibility buffer keeps the
// larger id. An id counts its unit by the scene's unit table (item order), not by the order the
// cull listed it in, which two-phase occlusion turns around here and which a GPU's atomic appends
// change between runs: the later item wins in every frame, through either rasteriser, so the
// strategy's files are reproducible. Item 0 holds the triangle alone; item 1 holds a far
// triangle, then the same one (its second: id unit * 256 + 1). The first frame sees only the far
// triangle, so the second frame's first phase lists item 1 and its second phase item 0 after it
// (counted in listed order, item 0's ids were the larger: it won).
TEST(VisibilityDepthTest, CoplanarTiesGoToTheLaterItemWhateverTheListOrder) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::array<glm::vec3, 3> shared{
        glm::vec3(-0.5f, -0.5f, 0.0f), glm::vec3(0.5f, -0.5f, 0.0f), glm::vec3(0.0f, 0.5f, 0.0f)};
    const std::array<glm::vec3, 3> far{glm::vec3(-4.5f, -0.5f, 0.0f), glm::vec3(-3.5f, -0.5f, 0.0f),
                                       glm::vec3(-4.0f, 0.5f, 0.0f)};
    test::GltfBuilder builder;
    const auto material = builder.addMaterial({.baseColor = {0.8f, 0.4f, 0.2f, 1.0f}});
    const auto alone = builder.addPositions({shared[0], shared[1], shared[2]});
    const auto after =
        builder.addPositions({far[0], far[1], far[2], shared[0], shared[1], shared[2]});
    builder.addScene({builder.addNode(
        {.mesh = builder.addMesh({{.attributes = {{"POSITION", alone}}, .material = material},
                                  {.attributes = {{"POSITION", after}}, .material = material}})})});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "ties.glb");
    ASSERT_TRUE(scene.ok());
    const float aspect = float(kWidth) / float(kHeight);
    const Camera seesFar =
        Camera::lookAt(glm::vec3(-4.0f, 0.0f, 1.2f), glm::vec3(-4.0f, 0.0f, 0.0f),
                       glm::radians(60.0f), aspect, 0.1f, 10.0f);
    const Camera seesShared = Camera::lookAt(glm::vec3(0.3f, 0.2f, 1.2f), glm::vec3(0.0f),
                                             glm::radians(60.0f), aspect, 0.1f, 10.0f);
    // Item 1's unit is the table's second (item 0 has one cluster): its triangles' ids.
    constexpr std::uint32_t kFarTriangle = 1 * VisibilityTables::kUnitTriangles;
    constexpr std::uint32_t kSharedTriangle = kFarTriangle + 1;
    struct Frame {
        Camera camera;
        std::uint32_t expectedId;
    };
    const std::array<Frame, 3> frames{Frame{seesFar, kFarTriangle},
                                      Frame{seesShared, kSharedTriangle},
                                      Frame{seesShared, kSharedTriangle}};
    for (const float pixels : {0.0f, VisibilityStrategy::kMaxWorkgroupPixels}) {
        SCOPED_TRACE("compute raster to " + std::to_string(pixels) + " pixels");
        auto renderer = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, 1));
        ASSERT_TRUE(renderer.ok());
        CullingOptions culling{.occlusion = true, .levelsOfDetail = false};
        culling.computeRasterPixels = std::min(pixels, VisibilityStrategy::kDefaultComputePixels);
        culling.workgroupRasterPixels = pixels;
        renderer->setCullingOptions(culling);
        ASSERT_TRUE(renderer->prepare(*scene, StrategyKind::Visibility).ok());
        for (const Frame& frame : frames) {
            renderer->renderFrame(frame.camera);
            const auto* strategy =
                dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
            auto entries = gpu::readBuffer(*context, strategy->visibilityBuffer(), 0,
                                           std::uint64_t(kWidth) * kHeight * 8);
            ASSERT_TRUE(entries.ok());
            std::size_t pixelsCovered = 0;
            std::size_t otherWinners = 0;
            for (std::size_t pixel = 0; pixel < std::size_t(kWidth) * kHeight; ++pixel) {
                if (covered(*entries, pixel)) {
                    ++pixelsCovered;
                    std::uint32_t id = 0;
                    std::memcpy(&id, entries->data() + pixel * 8, 4);
                    otherWinners += id != frame.expectedId;
                }
            }
            EXPECT_GT(pixelsCovered, std::size_t(kWidth) * kHeight / 8);
            EXPECT_EQ(otherWinners, 0u);
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility ties").ok());
}

}  // namespace
}  // namespace encore::render
