// The visibility strategy's frame before the render pass (docs/visibility.md, steps 1 to 3):
// the view slots' parameters, the cull of each view (or one for all views), its compute raster
// in one or two phases and the hardware raster of what compute does not take, then the shading
// (VisibilityShading.cpp); and where the last frame left its triangle counts.

#include "render/visibility/VisibilityStrategy.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "render/culling/CullingUniform.h"
#include "render/culling/LodSelection.h"
#include "render/visibility/VisibilityPhasePasses.h"

namespace encore::render {

namespace {

using ViewParams = VisibilityViewParams;

constexpr std::uint64_t kParamsStride = VisibilityTarget::kParamsStride;
constexpr std::uint64_t kCounterBytes = VisibilityPipelines::kCounterBytes;
// Byte offsets in visibility_raster.wgsl's Counters.
constexpr std::uint64_t kHardwareArguments = 16;
constexpr std::uint64_t kComputeTriangles = 32;  // Then the hardware triangles' count.
constexpr std::uint32_t kMaxGroups = 65535;

std::uint32_t groupsFor(std::uint64_t threads, std::uint32_t size) {
    return std::uint32_t((threads + size - 1) / size);
}

}  // namespace

void VisibilityStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    const std::size_t views = std::max<std::size_t>(frame.views.size(), 1);
    ensureTarget(frame.targetWidth, frame.targetHeight, views);
    // At one sample a frame composed in compute is shaded into place, its uncovered pixels
    // written by the binning (or the shading of a scene of one bin): no composition pass (on the
    // H100 0.018 ms of a 1280x720 frame).
    mComposedShading = frame.composedBackground.has_value() && mSetup->sampleCount == 1;
    if (mComposedShading) {
        ensureComposedShading(frame.composedView, *frame.composedBackground);
    }
    mLastViewCount = 0;
    mOcclusion = false;
    if (mTables.itemCount == 0 || frame.targetWidth == 0 || frame.targetHeight == 0) {
        return;
    }
    copyMaterialTable(commands);
    if (shadesEveryTile()) {
        writeEveryTileRecord();
    }
    // As GPU culling: two phases in frames of one view, and not while a frozen culling camera
    // sees another view than the one drawn.
    mOcclusion = views == 1 && frame.culling.occlusion && !frame.cullingCamera;
    // Frames of one view test items against the frustum by their world spheres while the
    // transforms hold still: computed in the first static frame, kept until one moves (a frame
    // that moves transforms tests with the matrices, so animation pays nothing for them).
    const bool moved = mTransformsMoved || frame.transformsAnimated;
    mTransformsMoved = false;
    mSpheresCurrent = mSpheresCurrent && !moved;
    mComputeSpheres = views == 1 && !moved && !mSpheresCurrent;
    mSpheresCurrent = mSpheresCurrent || mComputeSpheres;
    const std::uint32_t viewWidth = frame.targetWidth / std::uint32_t(views);
    if (!computeTakesAll(frame.culling)) {
        mTarget->ensureHardwareDepth(*mSetup, viewWidth);  // The hardware raster's attachment.
    }
    // A slot per view, then one per round of bins of each group of views that bins and shading
    // take at once.
    const std::size_t groups = VisibilityTarget::groupsFor(views);
    const std::uint32_t rounds = VisibilityTarget::roundsFor(mTables.binCount);
    std::vector<std::uint8_t> params(
        VisibilityTarget::slotsFor(views, mTables.binCount) * kParamsStride, 0);
    ViewParams p;
    p.itemCount = mTables.itemCount;
    p.targetWidth = frame.targetWidth;
    p.viewportHeight = frame.targetHeight;
    p.maxComputePixels = std::clamp(frame.culling.computeRasterPixels, 0.0f, kMaxComputePixels);
    p.maxWorkgroupPixels =
        std::clamp(frame.culling.workgroupRasterPixels, 0.0f, kMaxWorkgroupPixels);
    p.computeTakesAll = computeTakesAll(frame.culling) ? 1 : 0;
    p.frustumTest = views == 1 ? 1 : 0;
    p.hardwareCapacity = mHardwareCapacity;
    p.samples = mSetup->sampleCount;
    p.workgroupBlocks = mWorkgroupBlocks;
    p.workgroupRecords = mWorkgroupRecords;
    for (std::size_t view = 0; view < views; ++view) {
        p.viewportX = std::uint32_t(view) * viewWidth;
        p.viewportWidth = viewWidth;
        std::memcpy(params.data() + view * kParamsStride, &p, sizeof(p));
        // The view's frame uniform (what the renderer writes for it), for the shading of the
        // whole group: written with the slots rather than copied on the GPU view by view.
        const FrameUniform uniform = frameUniformOf(
            frame.views.empty() ? frame.camera : frame.views[view], frame.timeSeconds, view, views);
        std::memcpy(params.data() + view * kParamsStride + VisibilityTarget::kSlotFrameOffset,
                    &uniform, sizeof(uniform));
    }
    for (std::size_t group = 0; group < groups; ++group) {
        const std::size_t first = group * VisibilityTarget::kSlotViews;
        p.viewportX = std::uint32_t(first) * viewWidth;
        p.viewportWidth =
            std::uint32_t(std::min(views - first, VisibilityTarget::kSlotViews)) * viewWidth;
        for (std::uint32_t round = 0; round < rounds; ++round) {
            p.firstBin = round * VisibilityTarget::kRoundBins;
            std::memcpy(params.data() + (views + group * rounds + round) * kParamsStride, &p,
                        sizeof(p));
        }
    }
    mSetup->queue.WriteBuffer(mTarget->params, 0, params.data(), params.size());
    writeCullUniform(frame, views);
    // A multi-view frame's cull is the same for every view (no frustum test, no occlusion, the
    // levels of one cull for all views): it runs once, and each view's raster starts from the
    // counters it left.
    const bool culledOnce = views > 1;
    if (culledOnce) {
        encodeCull(commands, frame);
    }
    for (std::size_t group = 0; group < groups; ++group) {
        const std::size_t first = group * VisibilityTarget::kSlotViews;
        const std::size_t last = std::min(views, first + VisibilityTarget::kSlotViews);
        for (std::size_t view = first; view < last; ++view) {
            if (views > 1) {
                mSetup->frame->selectView(commands, view);  // The raster's group 0.
            }
            encodeView(commands, frame, view, viewWidth, culledOnce);
        }
        encodeShading(commands, frame, views, first, views + group * rounds,
                      std::uint32_t(last - first) * viewWidth);
    }
    mLastViewCount = views;
}

void VisibilityStrategy::encodeCull(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame) const {
    commands.CopyBufferToBuffer(mPipelines->initialCounters, 0, mCounters, 0, kCounterBytes);
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "visibility: culling";
    descriptor.timestampWrites =
        frame.timer ? frame.timer->nextPass("visibility culling") : nullptr;
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    dispatchClear(pass);
    const std::uint32_t paramsOffset = 0;
    pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
    pass.SetBindGroup(1, mCullGroup, 1, &paramsOffset);
    dispatchItems(pass, mPipelines->cullFirst);
    pass.End();
    commands.CopyBufferToBuffer(mCounters, 0, mCulledCounters, 0, kCounterBytes);
}

void VisibilityStrategy::dispatchClear(const wgpu::ComputePassEncoder& pass) const {
    const std::uint64_t entries = mTarget->visibility.GetSize() / 8;
    pass.SetPipeline(mPipelines->clear);
    pass.SetBindGroup(0, mClearGroup);
    pass.DispatchWorkgroups(
        std::uint32_t(std::min<std::uint64_t>((entries + 255) / 256, kMaxGroups)));
}

void VisibilityStrategy::dispatchItems(const wgpu::ComputePassEncoder& pass,
                                       const wgpu::ComputePipeline& cull) const {
    const std::uint32_t itemGroups = groupsFor(mTables.itemCount, 64);
    pass.SetPipeline(cull);
    pass.DispatchWorkgroups(std::min(itemGroups, kMaxGroups), groupsFor(itemGroups, kMaxGroups));
}

void VisibilityStrategy::writeCullUniform(const FrameState& frame, std::size_t views) const {
    // What GpuCuller's first phase writes for the same frame: the culling camera's frustum and
    // the levels of detail of one cull serving every view.
    const Camera& camera = frame.cullingCamera.value_or(frame.camera);
    CullingUniform uniform;
    fillCullingView(
        uniform, camera.projection * camera.view, views == 1,
        lodSelection(camera, frame.cullingCamera ? std::span<const Camera>() : frame.views,
                     frame.targetHeight, frame.culling));
    uniform.occlusion = mOcclusion ? 1 : 0;
    uniform.clusterCulling = frame.culling.clusterCulling ? 1 : 0;
    uniform.worldSpheres = views == 1 && mSpheresCurrent ? 1 : 0;
    uniform.unitListBase = mTables.unitListBase();
    mSetup->queue.WriteBuffer(mCullUniform, 0, &uniform, sizeof(uniform));
}

void VisibilityStrategy::encodeRaster(VisibilityPhasePasses& passes,
                                      std::uint32_t paramsOffset,
                                      bool secondPhase) const {
    auto dispatch = [&](const char* timerLabel, const wgpu::ComputePipeline& pipeline,
                        std::uint32_t groups) {
        const wgpu::ComputePassEncoder& pass = passes.step(timerLabel);
        pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
        pass.SetBindGroup(1, mRasterGroup, 1, &paramsOffset);
        pass.SetPipeline(pipeline);
        pass.DispatchWorkgroups(groups);
    };
    dispatch(secondPhase ? "visibility compute raster (second phase)" : "visibility compute raster",
             mPipelines->raster, mRasterGroups);
    dispatch(
        secondPhase ? "visibility workgroup raster (second phase)" : "visibility workgroup raster",
        mPipelines->workgroupRaster, mWorkgroupGroups);
}

void VisibilityStrategy::encodeHardwareRaster(const wgpu::CommandEncoder& commands,
                                              const FrameState& frame,
                                              std::uint32_t paramsOffset,
                                              std::uint32_t viewWidth,
                                              const char* timerLabel) const {
    if (computeTakesAll(frame.culling)) {
        return;  // The workgroup raster clipped what would have come here.
    }
    // The attachment only sets the pass's size and samples: the pipeline neither tests nor
    // writes it, so it is loaded and stored as it is (Dawn clears it once, on first use),
    // rather than cleared per view, which on the H100's graphics units took 0.06 ms per view
    // of 512x512 at four samples.
    wgpu::RenderPassDepthStencilAttachment depth{};
    depth.view = mTarget->hardwareDepthView;
    depth.depthLoadOp = wgpu::LoadOp::Load;
    depth.depthStoreOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "visibility: hardware raster";
    descriptor.depthStencilAttachment = &depth;
    descriptor.timestampWrites = frame.timer ? frame.timer->nextPass(timerLabel) : nullptr;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    // The attachment is one view's size: the view at the origin, its fragments shifted back to
    // the view's place in the strip (visibility_hardware.wgsl).
    pass.SetViewport(0.0f, 0.0f, float(viewWidth), float(mTarget->height), 0.0f, 1.0f);
    pass.SetPipeline(mPipelines->hardware);
    pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
    pass.SetBindGroup(1, mHardwareGroup, 1, &paramsOffset);
    pass.DrawIndirect(mCounters, kHardwareArguments);
    pass.End();
}

void VisibilityStrategy::encodeView(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame,
                                    std::size_t view,
                                    std::uint32_t viewWidth,
                                    bool culled) {
    const std::uint32_t paramsOffset = std::uint32_t(view * kParamsStride);
    auto bindCull = [&](const wgpu::ComputePassEncoder& pass) {
        pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
        pass.SetBindGroup(1, mCullGroup, 1, &paramsOffset);
    };
    const wgpu::Buffer& counters = culled ? mCulledCounters : mPipelines->initialCounters;
    commands.CopyBufferToBuffer(counters, 0, mCounters, 0, kCounterBytes);
    {
        // Everything in the frustum, or (two phases) what of it was visible last frame.
        VisibilityPhasePasses passes(commands, frame.timer,
                                     "visibility: culling and compute raster");
        if (!culled) {
            // The frame's first pass (one view): the clear runs beside the culling.
            const wgpu::ComputePassEncoder& pass = passes.step("visibility culling");
            dispatchClear(pass);
            bindCull(pass);
            if (mComputeSpheres) {
                dispatchItems(pass, mPipelines->worldSpheres);
            }
            dispatchItems(pass, mPipelines->cullFirst);
        }
        encodeRaster(passes, paramsOffset, false);
    }
    encodeHardwareRaster(commands, frame, paramsOffset, viewWidth, "visibility hardware raster");
    if (mOcclusion) {
        {
            // The rest of the frustum against the pyramid of what phase 1 drew (both rasters).
            VisibilityPhasePasses passes(commands, frame.timer,
                                         "visibility: depth pyramid, second culling and raster");
            mTarget->pyramid.encode(passes.step("visibility depth pyramid"));
            const wgpu::ComputePassEncoder& pass = passes.step("visibility occlusion culling");
            bindCull(pass);  // The pyramid's dispatches bound their own group 0.
            pass.SetPipeline(mPipelines->beginSecondPhase);
            pass.DispatchWorkgroups(1);
            dispatchItems(pass, mPipelines->cullSecond);
            encodeRaster(passes, paramsOffset, true);
        }
        encodeHardwareRaster(commands, frame, paramsOffset, viewWidth,
                             "visibility hardware raster (second phase)");
    }
    if (culled) {  // Frames of several views keep each one's counts; one view's stay put.
        commands.CopyBufferToBuffer(mCounters, kComputeTriangles, mTarget->triangleCounts, view * 8,
                                    8);
    }
}

StrategyReport VisibilityStrategy::report() const {
    StrategyReport report;
    if (mCullGroup) {  // Before the first frame the kept counts are another scene's.
        const std::uint64_t offset = rasterCountsOffset(0);
        report.gpuTriangleCounts =
            GpuTriangleCounts{rasterCounts(), offset + 4, offset, mTables.triangleCount};
    }
    return report;
}

const wgpu::Buffer& VisibilityStrategy::rasterCounts() const {
    return mLastViewCount > 1 ? mTarget->triangleCounts : mCounters;
}

std::uint64_t VisibilityStrategy::rasterCountsOffset(std::size_t view) const {
    return mLastViewCount > 1 ? view * 8 : kComputeTriangles;
}

}  // namespace encore::render
