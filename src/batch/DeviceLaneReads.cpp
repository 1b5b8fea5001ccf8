// DeviceLane's read-backs: starting them (through the ring, or the PNG rows pass), taking them
// in order as the GPU finishes, and handing their views to the writer (DeviceLane.h).

#include "batch/DeviceLane.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "batch/ModelOutput.h"
#include "batch/PassImages.h"
#include "core/Elapsed.h"
#include "render/GpuStage.h"

namespace encore::batch {
namespace {

using Clock = std::chrono::steady_clock;

Error lostWhileDrawing() {
    return makeError(ErrorCode::DeviceError,
                     "The GPU device was lost while the model's views were drawn.");
}

}  // namespace

void DeviceLane::collectOldest() {
    ChunkInFlight chunk = std::move(mChunks.front());
    mChunks.pop_front();
    auto finished = mRing->takeOldestMapped();
    if (!finished) {
        failJob(*chunk.job, "render", finished.error());
        recoverIfLost();
        return;
    }
    mStages.gpu += finished->waitMilliseconds / 1000.0;
    const auto start = Clock::now();
    if (!chunk.job->failed) {
        // The pool crops the strips straight out of the mapped buffer: the device thread copies
        // nothing, and the ring unmaps the buffer once the last strip is cropped.
        auto wide = std::make_shared<const gpu::MappedReadback>(std::move(*finished));
        if (chunk.pngRows) {
            mShared.writer.writePngRowViews(chunk.job, chunk.first, chunk.count,
                                            std::move(*chunk.pngRows), std::move(wide));
        } else if (!chunk.floatKinds.empty()) {
            mShared.writer.writeMappedFloatViews(chunk.job, chunk.first, chunk.count,
                                                 std::move(chunk.floatKinds), std::move(wide),
                                                 chunk.unitsPerModelUnit);
        } else {
            mShared.writer.writeViews(chunk.job, chunk.first, chunk.count, chunk.kind,
                                      std::move(wide));
        }
    }
    mStages.readback += secondsSince(start);
}

void DeviceLane::collectRenderer(std::size_t slot) {
    // The ring reads back in submission order: once the last read of the renderer's views is
    // taken, the GPU has finished everything the renderer submitted before it.
    const auto drewLast = [&] {
        return std::any_of(mChunks.begin(), mChunks.end(),
                           [&](const ChunkInFlight& chunk) { return chunk.renderer == slot; });
    };
    while (drewLast()) {
        collectOldest();
    }
}

void DeviceLane::collectReady() {
    while (!mChunks.empty() && mRing->oldestReady()) {
        collectOldest();
    }
}

void DeviceLane::renderChunk(const TargetViews& views, ViewImage kind, double& waiting) {
    const auto& [job, slot, cameras, first, count] = views;
    if (!waitForSlot(views, waiting)) {
        return;
    }
    render::Renderer& renderer = *mRenderers[slot].renderer;
    renderer.renderViews(cameras);
    if (kind == ViewImage::Color) {
        mViewsDrawn += count;
    }
    ChunkInFlight chunk{job, slot, first, count, kind};
    if (mPngRows) {
        const PngRowsRequest request{kind, pngRowsSourceOf(kind)};
        enqueuePngRows(views, renderer.target().outputBytesView(), {&request, 1}, 1.0f,
                       std::move(chunk), waiting);
        return;
    }
    enqueueReadback(views, renderer.target().colorTexture(), std::move(chunk), waiting);
}

bool DeviceLane::waitForSlot(const TargetViews& views, double& waiting) {
    if (!mRing->full()) {
        return true;
    }
    const auto waitStart = Clock::now();
    const std::uint64_t device = mDevicesLost;
    collectOldest();
    waiting += secondsSince(waitStart);
    if (device != mDevicesLost) {
        failJob(*views.job, "render", lostWhileDrawing());
        return false;
    }
    return true;
}

bool DeviceLane::enqueuePngRows(const TargetViews& views,
                                const wgpu::TextureView& source,
                                std::span<const PngRowsRequest> requests,
                                float depthFactor,
                                ChunkInFlight chunk,
                                double& waiting) {
    if (!waitForSlot(views, waiting)) {
        return false;
    }
    PngRowsLayout layout = pngRowsLayout(mLayout.width, mLayout.height, views.count, requests,
                                         mShared.options.pngCompression);
    auto enqueued = mRing->enqueueCommands(
        layout.size,
        [&](const wgpu::CommandEncoder& encoder, const wgpu::Buffer& destination) {
            mPngRows->record(mContext.queue(), encoder, source, layout, depthFactor, destination);
        },
        mTimestamps ? &*mTimestamps : nullptr,
        render::gpuStageIndex(render::GpuStage::ReadbackCopy));
    if (!enqueued) {
        failJob(*views.job, "render", enqueued.error());
        return false;
    }
    chunk.pngRows = std::move(layout);
    mChunks.push_back(std::move(chunk));
    return true;
}

bool DeviceLane::enqueueReadback(const TargetViews& views,
                                 const wgpu::Texture& texture,
                                 ChunkInFlight chunk,
                                 double& waiting) {
    if (!waitForSlot(views, waiting)) {
        return false;
    }
    auto enqueued = mRing->enqueue(texture, mTimestamps ? &*mTimestamps : nullptr,
                                   render::gpuStageIndex(render::GpuStage::ReadbackCopy));
    if (!enqueued) {
        failJob(*views.job, "render", enqueued.error());
        return false;
    }
    mChunks.push_back(std::move(chunk));
    return true;
}

void DeviceLane::readPassTargets(const TargetViews& views,
                                 float unitsPerModelUnit,
                                 double& waiting) {
    const auto& [job, slot, cameras, first, count] = views;
    const ExtraImages& images = mShared.options.images;
    // Depth as EXR and HDR are floats: those reads stay as they are; so does depth along rays,
    // whose factor varies per pixel (DepthConventions.h).
    const bool depthRows = mPngRows && !(images.depth && (images.depthFormat == DepthFormat::Exr ||
                                                          images.depthKind == DepthKind::Ray));
    std::vector<ViewImage> depthAndId;
    for (const ViewImage kind : extraPasses(images)) {
        if (job->failed) {
            return;
        }
        // The renderer may be gone after a device loss inside an earlier enqueue.
        const render::Renderer& renderer = *mRenderers[slot].renderer;
        ChunkInFlight chunk{job, slot, first, count, kind};
        chunk.unitsPerModelUnit = unitsPerModelUnit;
        if (kind == ViewImage::Depth || kind == ViewImage::Segmentation) {
            depthAndId.push_back(kind);  // One read for both, below.
            continue;
        }
        if (kind == ViewImage::Hdr) {
            chunk.floatKinds = {kind};
            enqueueReadback(views, renderer.target().sceneTexture(), std::move(chunk), waiting);
        } else if (mPngRows) {
            const PngRowsRequest request{kind, pngRowsSourceOf(kind)};
            enqueuePngRows(views, renderer.passBytesView(passImageOf(kind)), {&request, 1}, 1.0f,
                           std::move(chunk), waiting);
        } else {
            enqueueReadback(views, renderer.passTexture(passImageOf(kind)), std::move(chunk),
                            waiting);
        }
    }
    if (depthAndId.empty() || job->failed) {
        return;
    }
    const render::Renderer& renderer = *mRenderers[slot].renderer;
    ChunkInFlight chunk{job, slot, first, count, depthAndId.front()};
    chunk.unitsPerModelUnit = unitsPerModelUnit;
    if (depthRows) {
        std::vector<PngRowsRequest> requests;
        for (const ViewImage kind : depthAndId) {
            requests.push_back({kind, pngRowsSourceOf(kind)});
        }
        const float depthFactor =
            depthStepsPerUnit(unitsPerModelUnit, depthScale(mShared.options.views));
        enqueuePngRows(views, renderer.passBytesView(render::PassImage::DepthAndId), requests,
                       depthFactor, std::move(chunk), waiting);
        return;
    }
    chunk.floatKinds = std::move(depthAndId);
    enqueueReadback(views, renderer.passTexture(render::PassImage::DepthAndId), std::move(chunk),
                    waiting);
}

void DeviceLane::renderFloatPass(const TargetViews& views,
                                 ViewImage kind,
                                 float unitsPerModelUnit,
                                 double& waiting) {
    const auto& [job, slot, cameras, first, count] = views;
    render::Renderer& renderer = *mRenderers[slot].renderer;
    if (kind != ViewImage::Hdr) {
        renderer.renderViews(cameras);  // The HDR image is the colour frame's, drawn already.
    }
    // The HDR target holds the values themselves (the channels write them as colour); read back
    // now, waiting: float images are the exception.
    const auto start = Clock::now();
    auto wide = renderer.readHdrImage();
    mStages.gpu += secondsSince(start);
    waiting += secondsSince(start);
    if (!wide) {
        failJob(*job, "render", wide.error());
        return;
    }
    mShared.writer.writeFloatViews(job, first, count, kind, *wide, mLayout.targetWidth(),
                                   unitsPerModelUnit);
}

}  // namespace encore::batch
