#pragma once

// The visibility strategy's target-sized resources (docs/visibility.md): the visibility buffer,
// the binned tiles, the shaded colour, the hardware path's depth, the depth pyramid, and the
// per-view parameters and triangle counts. They depend on the target's size, its views, the
// sample count and (growing only) the scene's shading bins, so a renderer that prepares scene
// after scene at one size (encore batch) keeps them (KeptStrategyObjects) rather than
// allocating, clearing and reducing hundreds of megabytes, and building the pyramid's
// pipelines, for every model.

#include <webgpu/webgpu_cpp.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "render/RenderSetup.h"
#include "render/culling/DepthPyramid.h"

namespace encore::render {

struct VisibilityTarget {
    // The parameter slots: one per view (a dynamic uniform offset), its VisibilityViewParams
    // and, from kSlotFrameOffset, the view's frame uniform (copied there while encoding), then
    // one per group of views that binning and shading take at once, kSlotViews at most: as many
    // as one uniform binding of kSlotBindingBytes holds (visibility_geometry.wgsl's viewSlots).
    static constexpr std::uint64_t kParamsStride = 256;
    static constexpr std::uint64_t kSlotFrameOffset = 64;
    static constexpr std::uint64_t kSlotBindingBytes = 65536;
    static constexpr std::size_t kSlotViews = kSlotBindingBytes / kParamsStride;
    static std::size_t groupsFor(std::size_t views) {
        return (views + kSlotViews - 1) / kSlotViews;
    }
    // The 8x8 tiles across `pixels` (the binning's and the shading's unit, and the compute
    // composition's workgroups).
    static std::uint32_t tilesFor(std::uint32_t pixels) { return (pixels + 7) / 8; }
    // Bins that one binning dispatch lists (visibility_bin_record.wgsl's kRoundBins): the tile
    // list has room for every tile of a group of views in each; scenes of more bins bin and
    // shade in rounds, each group of views with a parameter slot per round.
    static constexpr std::uint32_t kRoundBins = 64;
    static std::uint32_t roundsFor(std::uint32_t bins) {
        return std::max<std::uint32_t>((bins + kRoundBins - 1) / kRoundBins, 1);
    }
    // The parameter slots of a frame: one per view, then one per round of each group of views.
    static std::size_t slotsFor(std::size_t views, std::uint32_t bins) {
        return views + groupsFor(views) * roundsFor(bins);
    }

    // Makes the resources for `width` x `height` (`views` side by side, a scene of `bins`
    // shading bins) where they are not already; returns whether anything was made again (bind
    // groups over it must be too).
    bool ensure(const RenderSetup& setup,
                std::uint32_t width,
                std::uint32_t height,
                std::size_t views,
                std::uint32_t bins,
                std::uint32_t maxGroups);
    // The hardware raster's depth attachment at one view's size: its pass draws one view (its
    // viewport at the origin; the fragments add the view's offset), and clearing a whole strip
    // of views' multisampled depth for each view cost more than the pass's drawing (H100: 0.9 ms
    // per pass at 6144x512 and four samples).
    void ensureHardwareDepth(const RenderSetup& setup, std::uint32_t viewWidth);

    // Bytes of visibility_composed.wgsl's Composition: the background.
    static constexpr std::uint64_t kCompositionBytes = 16;

    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::size_t viewCapacity = 0;
    std::size_t slotCapacity = 0;
    std::uint32_t tileBins = 0;  // Bins the tile list has room for.
    // Workgroups of each bin's shading grid: at most the tiles of the target.
    std::uint32_t shadeGroups = 1;
    wgpu::Buffer params;          // The parameter slots, and a binding's worth past them.
    wgpu::Buffer triangleCounts;  // Per view: compute, hardware.
    wgpu::Buffer visibility;
    // Per bin of a binning round, room for every 8x8 tile of the target (visibility_bins.wgsl).
    wgpu::Buffer tiles;
    wgpu::Texture shaded;
    wgpu::TextureView shadedLayers;  // Every layer (one per sample), as an array.
    wgpu::Texture hardwareDepth;     // One view's size (ensureHardwareDepth).
    wgpu::TextureView hardwareDepthView;
    DepthPyramid pyramid;  // Of the visibility buffer's depth.
    // The composed frame's view of the target (FramePasses::composeFrame), its Composition
    // uniform and the words last written there (ensureComposed).
    wgpu::TextureView composedView;
    wgpu::Buffer composition;
    std::array<std::uint32_t, kCompositionBytes / 4> compositionWords{};

    // Takes the frame's view of the target (FrameState::composedView), and writes the
    // Composition uniform (`background`) where it changed; returns whether the view is another
    // than the last frame's (bind groups over it must be made again).
    bool ensureComposed(const RenderSetup& setup,
                        const wgpu::TextureView& view,
                        const wgpu::Color& background);
};

}  // namespace encore::render
