// Segmentation ids at 4 samples (RenderTargetOptions::exactIds, render/SampleIdPass.h): each
// pixel's id is one sample's, a real id, where the resolve would average two objects' ids into
// one that neither has; the colour stays antialiased. Both ways of drawing ids are checked: the
// segmentation channel's frame and the DepthAndId pass target, with every strategy that draws
// them.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "GeneratedModels.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 48;
constexpr StrategyKind kStrategies[] = {StrategyKind::Materials, StrategyKind::Bundles,
                                        StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles};
const Camera kCamera = Camera::lookAt({0.0f, 0.0f, 3.0f}, {0, 0, 0}, 0.8f, 1.0f, 0.1f, 10.0f);

struct Frame {
    std::vector<std::uint32_t> ids;
    std::vector<float> coverage;  // The shaded frame's alpha.
};

// The ids of texels that hold id % 256 in `low`, id / 256 in the next channel and coverage in
// the fourth, both ids times coverage: 0 where less than half is covered (encore batch's rule).
std::vector<std::uint32_t> decodeIds(const std::vector<float>& texels, std::size_t low) {
    std::vector<std::uint32_t> ids(texels.size() / 4);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const float* texel = &texels[i * 4];
        if (texel[3] >= 0.5f) {
            ids[i] = std::uint32_t(std::lround(texel[low] / texel[3]) +
                                   256 * std::lround(texel[low + 1] / texel[3]));
        }
    }
    return ids;
}

// Draws `scene` with each strategy at `samples`, the ids through the segmentation channel or the
// pass target.
std::vector<Frame> drawIds(gpu::Context& context,
                           const scene::SceneData& scene,
                           std::uint32_t samples,
                           bool exactIds,
                           bool passTargets) {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, samples, DebugChannel::Shaded);
    options.target.hdr = true;
    options.target.exactIds = exactIds;
    options.toneMapping.background = BackgroundKind::Transparent;
    options.passTargets = passTargets ? PassTargets::SegmentByNode : PassTargets::None;
    auto renderer = Renderer::create(context, options);
    EXPECT_TRUE(renderer.ok()) << renderer.error().message;
    std::vector<Frame> frames;
    for (const StrategyKind kind : kStrategies) {
        EXPECT_TRUE(renderer->prepare(scene, kind).ok());
        Frame frame;
        LightingParameters lighting = renderer->lighting();
        lighting.debugChannel = DebugChannel::Shaded;
        renderer->setLighting(lighting);
        renderer->renderFrame(kCamera);
        auto shaded = renderer->readHdrImage();
        EXPECT_TRUE(shaded.ok());
        for (std::size_t i = 3; i < shaded->size(); i += 4) {
            frame.coverage.push_back((*shaded)[i]);
        }
        if (passTargets) {
            auto depthAndId =
                gpu::readTextureRgba16Float(context, renderer->passTexture(PassImage::DepthAndId));
            EXPECT_TRUE(depthAndId.ok());
            frame.ids = decodeIds(*depthAndId, 1);
        } else {
            lighting.debugChannel = DebugChannel::SegmentNode;
            renderer->setLighting(lighting);
            renderer->renderFrame(kCamera);
            auto hdr = renderer->readHdrImage();
            EXPECT_TRUE(hdr.ok());
            frame.ids = decodeIds(*hdr, 0);
        }
        EXPECT_TRUE(context.checkNoErrors("Drawing segmentation ids").ok());
        frames.push_back(std::move(frame));
    }
    return frames;
}

// The ids within one pixel of (x, y).
std::set<std::uint32_t> neighbourhood(const std::vector<std::uint32_t>& ids,
                                      std::uint32_t x,
                                      std::uint32_t y) {
    std::set<std::uint32_t> found;
    for (std::uint32_t ny = y == 0 ? 0 : y - 1; ny <= std::min(y + 1, kSize - 1); ++ny) {
        for (std::uint32_t nx = x == 0 ? 0 : x - 1; nx <= std::min(x + 1, kSize - 1); ++nx) {
            found.insert(ids[std::size_t(ny) * kSize + nx]);
        }
    }
    return found;
}

TEST(ExactIdsTest, FourSamplesGiveTheIdsOfOneSampleAndAntialiasedColour) {
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadSceneFromMemory(test::cutSquareGlb(0.8f, 0.3f), {}, "cut.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::set<std::uint32_t> drawn = {0, 1, 4};
    for (const bool passTargets : {false, true}) {
        SCOPED_TRACE(passTargets ? "pass target" : "segmentation channel");
        const std::vector<Frame> ones = drawIds(*context, *scene, 1, true, passTargets);
        const std::vector<Frame> fours = drawIds(*context, *scene, 4, true, passTargets);
        const std::vector<Frame> averaged = drawIds(*context, *scene, 4, false, passTargets);
        ASSERT_EQ(ones.size(), std::size(kStrategies));
        ASSERT_EQ(fours.size(), std::size(kStrategies));
        ASSERT_EQ(averaged.size(), std::size(kStrategies));
        for (std::size_t s = 0; s < std::size(kStrategies); ++s) {
            SCOPED_TRACE(std::string(strategyName(kStrategies[s])));
            const Frame& one = ones[s];
            const Frame& four = fours[s];
            std::size_t cut = 0, differing = 0, partial = 0, averagedOthers = 0;
            for (std::uint32_t y = 0; y < kSize; ++y) {
                for (std::uint32_t x = 0; x < kSize; ++x) {
                    const std::size_t i = std::size_t(y) * kSize + x;
                    ASSERT_TRUE(drawn.count(four.ids[i])) << four.ids[i] << " at " << x << "," << y;
                    const std::set<std::uint32_t> around = neighbourhood(one.ids, x, y);
                    cut += around.count(1) && around.count(4);
                    if (four.ids[i] != one.ids[i]) {
                        ++differing;
                        EXPECT_GT(around.size(), 1u) << "not an edge pixel: " << x << "," << y;
                    }
                    // The colour: partly covered edges at 4 samples only.
                    EXPECT_TRUE(one.coverage[i] == 0.0f || one.coverage[i] == 1.0f);
                    partial += four.coverage[i] > 0.0f && four.coverage[i] < 1.0f;
                    averagedOthers += !drawn.count(averaged[s].ids[i]);
                }
            }
            EXPECT_GT(cut, kSize / 2) << "the cut between ids 1 and 4 crosses the image";
            EXPECT_LT(differing, cut + 4 * kSize) << "only edge pixels may differ";
            EXPECT_GT(partial, kSize) << "the colour is antialiased at 4 samples";
            // Without exact ids the resolve averages the ids along the cut: this scene shows it.
            EXPECT_GT(averagedOthers, 0u) << "the resolve made no id that was not drawn";
            // Inside either piece, the ids of both sample counts agree.
            EXPECT_EQ(four.ids[std::size_t(kSize / 2 + 8) * kSize + kSize / 2 + 8], 1u);
            EXPECT_EQ(four.ids[std::size_t(kSize / 2 - 8) * kSize + kSize / 2 - 8], 4u);
        }
    }
}

}  // namespace
}  // namespace encore::render
