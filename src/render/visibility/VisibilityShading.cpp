// The visibility strategy's steps after the raster (docs/visibility.md, steps 4 and 5, and the
// frame's composition): tiles binned per shading bin, each bin shaded by a dispatch of its own
// (its materials' uniforms from the material table), and the frame composed in compute or
// shaded into place.

#include "render/visibility/VisibilityStrategy.h"

#include <array>
#include <cstdint>
#include <vector>

#include "gpu/BindingResource.h"
#include "render/MaterialResources.h"
#include "render/visibility/MaterialBins.h"
#include "render/visibility/VisibilityPhasePasses.h"

namespace encore::render {

std::vector<gpu::BindingResource> VisibilityStrategy::binResources() const {
    const VisibilityTarget& target = *mTarget;
    return {{0, target.params, 0, sizeof(VisibilityViewParams)},
            {1, mTableBuffer},
            {2, mWork->units},
            {3, target.visibility},
            {4, mWork->bins},
            {5, target.tiles}};
}

std::vector<gpu::BindingResource> VisibilityStrategy::shadeResources() const {
    const VisibilityTarget& target = *mTarget;
    return {{0, target.params, 0, VisibilityTarget::kSlotBindingBytes},
            {1, mGeometry, 0, mGeometryBytes},
            {2, mScene->instances().buffer()},
            {3, mTableBuffer},
            {4, mWork->units},
            {5, target.visibility},
            {6, target.tiles},
            {7, mWork->bins, 0, kBinRecordBytes},
            {10, mMaterialTable, 0, MaterialBins::kBlockBytes}};
}

void VisibilityStrategy::copyMaterialTable(const wgpu::CommandEncoder& commands) {
    const MaterialResources& materials = mScene->materials();
    if (mCopiedMaterials == materials.uniformGeneration()) {
        return;
    }
    const MaterialBins& bins = mTables.materialBins;
    for (std::uint32_t material = 0; material < bins.materialCount(); ++material) {
        commands.CopyBufferToBuffer(materials.uniformBuffer(), material * materials.uniformStride(),
                                    mMaterialTable, bins.slotOffset(material),
                                    sizeof(MaterialUniform));
    }
    mCopiedMaterials = materials.uniformGeneration();
}

void VisibilityStrategy::ensureComposedShading(const wgpu::TextureView& view,
                                               const wgpu::Color& background) {
    if (!mTarget->ensureComposed(*mSetup, view, background) && mBinComposedGroup) {
        return;
    }
    const wgpu::Device& device = mSetup->device;
    const VisibilityTarget& target = *mTarget;
    std::vector<gpu::BindingResource> bins = binResources();
    bins.emplace_back(6, target.composedView);
    bins.emplace_back(7, target.composition);
    mBinComposedGroup = gpu::makeBindGroup(device, mPipelines->binComposedLayout, bins,
                                           "visibility bins, composed");
    std::vector<gpu::BindingResource> shading = shadeResources();
    shading.emplace_back(8, target.composedView);
    shading.emplace_back(9, target.composition);
    mShadeComposedGroup = gpu::makeBindGroup(device, mPipelines->shadeComposedLayout, shading,
                                             "visibility shading, composed");
}

void VisibilityStrategy::encodeShading(const wgpu::CommandEncoder& commands,
                                       const FrameState& frame,
                                       std::size_t views,
                                       std::size_t firstView,
                                       std::size_t firstBinSlot,
                                       std::uint32_t groupWidth) const {
    VisibilityPhasePasses passes(commands, frame.timer, "visibility: binning and shading");
    const std::uint32_t slotsOffset = std::uint32_t(firstView * VisibilityTarget::kParamsStride);
    if (shadesEveryTile()) {
        // The bin's record, written by beforePass, says so: no binning.
        const wgpu::ComputePassEncoder& pass = passes.step("visibility shading");
        pass.SetBindGroup(0, mSetup->frame->bindGroup());
        shadeBin(pass, mTables.bins.front(), views, slotsOffset);
        return;
    }
    commands.ClearBuffer(mWork->bins, 0, std::uint64_t(mTables.binCount) * kBinRecordBytes);
    const std::uint32_t columns = VisibilityTarget::tilesFor(groupWidth);
    const std::uint32_t rows = VisibilityTarget::tilesFor(mTarget->height);
    // Round after round of kRoundBins (one, unless the scene has more): its tiles listed, then
    // its bins shaded, a dispatch each (mTables.bins is in order).
    for (auto bin = mTables.bins.begin(); bin != mTables.bins.end();) {
        const std::uint32_t round = *bin / VisibilityTarget::kRoundBins;
        const std::uint32_t roundEnd = (round + 1) * VisibilityTarget::kRoundBins;
        const wgpu::ComputePassEncoder& binning = passes.step("visibility binning");
        const std::uint32_t binOffset =
            std::uint32_t((firstBinSlot + round) * VisibilityTarget::kParamsStride);
        binning.SetBindGroup(0, mComposedShading ? mBinComposedGroup : mBinGroup, 1, &binOffset);
        binning.SetPipeline(mComposedShading ? mPipelines->binTilesComposed : mPipelines->binTiles);
        binning.DispatchWorkgroups(columns, rows);
        const wgpu::ComputePassEncoder& pass = passes.step("visibility shading");
        pass.SetBindGroup(0, mSetup->frame->bindGroup());
        for (; bin != mTables.bins.end() && *bin < roundEnd; ++bin) {
            shadeBin(pass, *bin, views, slotsOffset);
        }
    }
}

void VisibilityStrategy::shadeBin(const wgpu::ComputePassEncoder& pass,
                                  std::uint32_t bin,
                                  std::size_t views,
                                  std::uint32_t slotsOffset) const {
    const MaterialResources& materials = mScene->materials();
    const scene::MaterialId material(bin / 2);
    const wgpu::ComputePipeline& shading =
        mPipelines->shading(*mSetup, views > 1, materials.textured(material), (bin & 1) != 0,
                            materials.shadesExtensions(material), mComposedShading);
    if (!shading) {
        return;  // An embedded shader that does not compile: a bug the tests show.
    }
    pass.SetPipeline(shading);
    const std::uint32_t offsets[] = {slotsOffset, std::uint32_t(bin * kBinRecordBytes),
                                     mTables.materialBins.blockOffset(bin)};
    pass.SetBindGroup(1, mComposedShading ? mShadeComposedGroup : mShadeGroup, 3, offsets);
    pass.SetBindGroup(2, materials.drawBindGroup(material));
    pass.DispatchWorkgroups(mTarget->shadeGroups);
}

void VisibilityStrategy::writeEveryTileRecord() const {
    // visibility_shade.wgsl's Bin: no tile listed, the bin's id, every tile.
    const std::uint32_t bin = mTables.bins.front();
    const std::array<std::uint32_t, 4> record{0, bin, 0, 1};
    mSetup->queue.WriteBuffer(mWork->bins, std::uint64_t(bin) * kBinRecordBytes, record.data(),
                              sizeof(record));
}

bool VisibilityStrategy::composesFrame(const FrameState& frame) const {
    return mTables.itemCount > 0 && !drawsAfter() && frame.targetWidth > 0 &&
           frame.targetHeight > 0;
}

void VisibilityStrategy::composeFrame(const wgpu::CommandEncoder& commands,
                                      const FrameState& frame,
                                      const FrameComposition& target) {
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "visibility: composition";
    descriptor.timestampWrites = target.timestampWrites;
    if (mComposedShading) {
        // Shaded into place (beforePass): nothing is left. A timed frame still closes the pass
        // its timer counts on, with nothing in it.
        if (target.timestampWrites) {
            commands.BeginComputePass(&descriptor).End();
        }
        return;
    }
    if (mTarget->ensureComposed(*mSetup, frame.composedView, target.background) || !mComposeGroup) {
        mComposeGroup = gpu::makeBindGroup(mSetup->device, mPipelines->composeLayout,
                                           {{0, mTarget->visibility},
                                            {1, mTarget->shadedLayers},
                                            {2, frame.composedView},
                                            {3, mTarget->composition}},
                                           "visibility composition");
    }
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    pass.SetPipeline(mPipelines->compose);
    pass.SetBindGroup(0, mComposeGroup);
    pass.DispatchWorkgroups(VisibilityTarget::tilesFor(mTarget->width),
                            VisibilityTarget::tilesFor(mTarget->height));
    pass.End();
}

}  // namespace encore::render
