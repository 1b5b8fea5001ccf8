// RendererCore's frames: the frame uniforms, one render pass per view (or the two passes of a
// two-phase frame) recorded by the strategy, with transmissive surfaces the copy and one
// transmission pass per view (TransmissionPass.h), tone mapping, timing and submission; then
// the triangle counts of GPU culling and the image read back.

#include "render/renderer/RendererCore.h"

#include <array>
#include <optional>
#include <span>

#include "gpu/Readback.h"
#include "gpu/TimedSubmit.h"
#include "render/FramePasses.h"
#include "render/PassAttachments.h"
#include "render/PassTargets.h"
#include "render/SampleIdPass.h"
#include "render/TransmissionPass.h"
#include "render/TriangleHistory.h"

namespace encore::render {

FrameResult RendererCore::renderFrame(const Camera& camera,
                                      float timeSeconds,
                                      std::vector<RecordedCall>* trace) {
    return renderPasses(std::span(&camera, 1), timeSeconds, trace);
}

FrameResult RendererCore::renderViews(std::span<const Camera> cameras, float timeSeconds) {
    return renderPasses(cameras, timeSeconds, nullptr);
}

const wgpu::PassTimestampWrites* RendererCore::timestampWrites(GpuStage stage,
                                                               std::string_view label) {
    if (mTimer) {
        return mTimer->nextPass(label);
    }
    return mStageTimestamps ? mStageTimestamps->pass(gpuStageIndex(stage)) : nullptr;
}

// What one frame draws and how, decided before anything is recorded.
struct RendererCore::FramePlan {
    std::span<const Camera> cameras;
    FrameState state;
    bool multiView = false;
    bool twoPhases = false;
    // Only scenes with transmissive surfaces pay for the copy and the extra passes.
    bool transmission = false;
    // Straight into the resolved texture at one sample (FramePasses::composesResolved).
    bool resolvedPasses = false;
    // Every pixel composed in compute (FramePasses::composesFrame): no scene render pass at all.
    std::optional<PassAttachments> composedAttachments;
    // Segmentation ids from sample 0 (SampleIdPass): the multisampled colour is stored.
    bool sampleIds = false;
    std::vector<RecordedCall>* trace = nullptr;
};

namespace {

bool drawsIds(DebugChannel channel) {
    return channel == DebugChannel::SegmentNode || channel == DebugChannel::SegmentMesh ||
           channel == DebugChannel::SegmentMaterial;
}

}  // namespace

FrameResult RendererCore::renderPasses(std::span<const Camera> cameras,
                                       float timeSeconds,
                                       std::vector<RecordedCall>* trace) {
    FrameResult result;
    if (cameras.empty()) {
        return result;
    }
    if (cameras.size() > 1) {
        mFrame->writeViews(mContext->device(), mContext->queue(), cameras, timeSeconds);
    } else {
        mFrame->update(mContext->queue(), cameras[0], timeSeconds);
    }
    const FramePlan plan = planFrame(cameras, timeSeconds, trace);
    const gpu::SubmitTiming timing =
        gpu::submitTimed(*mContext, mTimer, [&](const wgpu::CommandEncoder& commandEncoder) {
            encodeFrame(commandEncoder, plan, result);
        });
    result.encodeMilliseconds = timing.encodeMilliseconds;
    result.submitMilliseconds = timing.submitMilliseconds;
    result.gpuMilliseconds = timing.gpuMilliseconds;
    const StrategyReport report = mStrategy ? mStrategy->report() : StrategyReport{};
    result.bundleContents = report.bundleContents;
    // Bundles and indirect draws replay per view; counters already sum the direct draws.
    const auto& gpuCounts = report.gpuTriangleCounts;
    result.trianglesSubmitted =
        result.counters.triangles + cameras.size() * (result.bundleContents.triangles +
                                                      (gpuCounts ? gpuCounts->candidates : 0));
    return result;
}

RendererCore::FramePlan RendererCore::planFrame(std::span<const Camera> cameras,
                                                float timeSeconds,
                                                std::vector<RecordedCall>* trace) const {
    FramePlan plan;
    plan.cameras = cameras;
    plan.trace = trace;
    plan.multiView = cameras.size() > 1;
    FrameState& state = plan.state;
    state = FrameState{cameras[0], cameras, timeSeconds, mTimer, mCullingCamera};
    state.culling = mOptions.culling;
    state.targetWidth = mTarget.width();
    state.targetHeight = mTarget.height();
    state.transformsAnimated = mGpuAnimation && mGpuAnimationPending;
    FramePasses* passes = mStrategy ? mStrategy->framePasses() : nullptr;
    plan.twoPhases = !plan.multiView && passes && passes->drawsInTwoPhases(state);
    if (plan.twoPhases) {
        state.phase = DrawPhase::First;
    }

    plan.transmission = mTransmission && passes && passes->drawsTransmission();
    // One scene pass, of colour alone: what a strategy may compose some other way.
    const bool singlePass = mStrategy && !plan.twoPhases && !plan.transmission && !mPassTargets;
    plan.resolvedPasses = singlePass && passes && mResolvedBackground && passes->composesResolved();
    const bool composedFrame = singlePass && passes &&
                               mOptions.toneMapping.background != BackgroundKind::Environment &&
                               passes->composesFrame(state);
    if (composedFrame) {
        PassPlan composedPass;
        composedPass.viewCount = cameras.size();
        composedPass.hdr = mTarget.hdr();
        composedPass.backgroundColor = mOptions.toneMapping.backgroundColor;
        plan.composedAttachments = passAttachments(composedPass);
        state.composedBackground = plan.composedAttachments->clearColor;
        state.composedView = mTarget.sceneStorageView();
    }
    plan.sampleIds = mSceneIds && !plan.resolvedPasses && !plan.composedAttachments &&
                     drawsIds(mLighting->parameters().debugChannel);
    return plan;
}

void RendererCore::encodeFrame(const wgpu::CommandEncoder& commandEncoder,
                               const FramePlan& plan,
                               FrameResult& result) {
    if (mGpuAnimation && mGpuAnimationPending) {
        mGpuAnimation->encode(commandEncoder);  // Before anything that reads its results.
        mGpuAnimationPending = false;
    }
    if (mStrategy && mStageTimestamps) {
        mStageTimestamps->timeCommands(commandEncoder, gpuStageIndex(GpuStage::BeforePasses),
                                       [&] { mStrategy->beforePass(commandEncoder, plan.state); });
    } else if (mStrategy) {
        mStrategy->beforePass(commandEncoder, plan.state);
    }
    encodeScenePasses(commandEncoder, plan, result);
    if (plan.transmission) {
        encodeTransmissionPasses(commandEncoder, plan, result);
    }
    if (plan.sampleIds) {
        mSceneIds->encode(commandEncoder, mTarget.sceneView());  // Before tone mapping reads it.
    }
    // After the last pass: a two-phase frame counts in both culling passes.
    if (mTriangleHistory && mStrategy) {
        if (auto counts = mStrategy->report().gpuTriangleCounts) {
            mTriangleHistory->record(commandEncoder, *counts);
        }
    }
    if (mToneMapper) {
        // The GPU timer times the scene passes only, as benchmarks report them.
        mToneMapper->encode(commandEncoder, mTarget,
                            mTimer ? nullptr : timestampWrites(GpuStage::ToneMapping));
    }
    if (mPassTargets) {
        mPassTargets->encodeImages(commandEncoder);
    }
}

void RendererCore::encodeScenePasses(const wgpu::CommandEncoder& commandEncoder,
                                     const FramePlan& plan,
                                     FrameResult& result) {
    if (plan.composedAttachments) {
        FrameComposition composition;
        composition.background = plan.composedAttachments->clearColor;
        composition.timestampWrites =
            timestampWrites(GpuStage::Scene, plan.composedAttachments->timestampLabel);
        mStrategy->framePasses()->composeFrame(commandEncoder, plan.state, composition);
    } else if (plan.twoPhases) {
        encodeScenePass(commandEncoder, plan, 0, DrawPhase::First, false, result);
        mStrategy->framePasses()->betweenPhases(commandEncoder, plan.state, mTarget.depthTexture());
        encodeScenePass(commandEncoder, plan, 0, DrawPhase::Second, false, result);
    } else {
        for (std::size_t view = 0; view < plan.cameras.size(); ++view) {
            if (plan.multiView) {
                mFrame->selectView(commandEncoder, view);
            }
            encodeScenePass(commandEncoder, plan, view, DrawPhase::Whole, false, result);
        }
    }
}

void RendererCore::encodeTransmissionPasses(const wgpu::CommandEncoder& commandEncoder,
                                            const FramePlan& plan,
                                            FrameResult& result) {
    // Everything but the transmissive surfaces is drawn (and resolved): copy it once for
    // all views, then draw them over it view by view.
    mTransmission->encodeCopy(commandEncoder, mTarget.sceneView(), mTimer);
    ++result.transmissionCopies;
    for (std::size_t view = 0; view < plan.cameras.size(); ++view) {
        if (plan.multiView) {
            mFrame->selectView(commandEncoder, view);
        }
        encodeScenePass(commandEncoder, plan, view,
                        plan.twoPhases ? DrawPhase::Second : DrawPhase::Whole, true, result);
    }
}

// One pass per view, or the two passes of a two-phase frame; what each loads, keeps and
// resolves is passAttachments' decision (PassAttachments.h).
void RendererCore::encodeScenePass(const wgpu::CommandEncoder& commandEncoder,
                                   const FramePlan& plan,
                                   std::size_t view,
                                   DrawPhase phase,
                                   bool transmissionPass,
                                   FrameResult& result) {
    PassPlan passPlan;
    passPlan.view = view;
    passPlan.viewCount = plan.cameras.size();
    passPlan.phase = phase;
    passPlan.multisampled = mTarget.sampleCount() > 1 && !plan.resolvedPasses;
    passPlan.hdr = mTarget.hdr();
    passPlan.backgroundColor = mOptions.toneMapping.backgroundColor;
    passPlan.transmission = transmissionPass;
    passPlan.transmissionFollows =
        plan.transmission && !transmissionPass && phase != DrawPhase::First;
    const PassAttachments attachments = passAttachments(passPlan);
    wgpu::RenderPassColorAttachment color =
        plan.resolvedPasses ? mTarget.resolvedColorAttachment(attachments.clearColor)
                            : mTarget.colorAttachment(attachments.clearColor);
    color.loadOp = attachments.colorLoadOp;
    color.storeOp = attachments.colorStoreOp;
    if (!attachments.resolve) {
        color.resolveTarget = nullptr;
    }
    if (plan.sampleIds) {
        color.storeOp = wgpu::StoreOp::Store;  // The id pass reads the samples after the last.
    }
    wgpu::RenderPassDepthStencilAttachment depth = mTarget.depthAttachment();
    depth.depthLoadOp = attachments.depthLoadOp;
    depth.depthStoreOp = attachments.depthStoreOp;
    depth.depthClearValue = attachments.depthClearValue;
    // With pass targets, the pass images follow the colour (PassTargets.h).
    // On the stack: a frame allocates nothing for its passes.
    std::array<wgpu::RenderPassColorAttachment, 1 + kPassTargetCount> colors;
    colors[0] = color;
    std::size_t colorCount = 1;
    if (mPassTargets) {
        mPassTargets->fillAttachments(color, std::span(colors).subspan<1, kPassTargetCount>());
        colorCount += kPassTargetCount;
    }
    wgpu::RenderPassDescriptor passDescriptor{};
    passDescriptor.label = attachments.label;
    passDescriptor.colorAttachmentCount = colorCount;
    passDescriptor.colorAttachments = colors.data();
    passDescriptor.depthStencilAttachment = plan.resolvedPasses ? nullptr : &depth;
    // The transmission pass is timed by the GPU timer only (stage timestamps time one
    // scene pass per view).
    passDescriptor.timestampWrites =
        transmissionPass ? (mTimer ? mTimer->nextPass(attachments.timestampLabel) : nullptr)
                         : timestampWrites(GpuStage::Scene, attachments.timestampLabel);
    wgpu::RenderPassEncoder pass = commandEncoder.BeginRenderPass(&passDescriptor);
    drawView(pass, plan, view, phase, transmissionPass, result);
    pass.End();
}

void RendererCore::drawView(const wgpu::RenderPassEncoder& pass,
                            const FramePlan& plan,
                            std::size_t view,
                            DrawPhase phase,
                            bool transmissionPass,
                            FrameResult& result) {
    if (plan.multiView) {
        const std::uint32_t viewWidth = mTarget.width() / std::uint32_t(plan.cameras.size());
        pass.SetViewport(float(view * viewWidth), 0.0f, float(viewWidth), float(mTarget.height()),
                         0.0f, 1.0f);
        // Clipping keeps a view's fragments inside its viewport already; the scissor makes
        // sure no rounding reaches the neighbouring strips, whose colour and depth persist.
        pass.SetScissorRect(view * viewWidth, 0, viewWidth, mTarget.height());
    }
    if (mOptions.toneMapping.background == BackgroundKind::Environment &&
        phase != DrawPhase::Second && !transmissionPass) {
        (plan.resolvedPasses ? mResolvedBackground : mBackground)->draw(pass, mFrame->bindGroup());
    }
    if (mStrategy) {
        RenderEncoder encoder(pass, result.counters);
        encoder.setTrace(plan.trace);
        FrameState viewState = plan.state;
        viewState.camera = plan.cameras[view];
        viewState.phase = phase;
        viewState.resolvedPass = plan.resolvedPasses;
        if (transmissionPass) {
            mStrategy->framePasses()->encodeTransmission(encoder, viewState);
        } else {
            mStrategy->encode(encoder, viewState);
        }
    }
}

void RendererCore::toneMapScene() {
    if (!mToneMapper) {
        return;
    }
    wgpu::CommandEncoder commands = mContext->device().CreateCommandEncoder();
    mToneMapper->encode(commands, mTarget);
    wgpu::CommandBuffer buffer = commands.Finish();
    mContext->queue().Submit(1, &buffer);
}

void RendererCore::setTriangleCounting(bool on) {
    mTriangleHistory = on ? std::make_unique<TriangleHistory>(mContext->device()) : nullptr;
}

Result<std::vector<DrawnTriangles>> RendererCore::takeTriangleHistory() {
    if (!mTriangleHistory) {
        return std::vector<DrawnTriangles>{};
    }
    return mTriangleHistory->take(*mContext);
}

Result<std::vector<std::uint64_t>> RendererCore::takeDrawnTriangles() {
    ENCORE_TRY_ASSIGN(auto history, takeTriangleHistory());
    std::vector<std::uint64_t> totals;
    totals.reserve(history.size());
    for (const DrawnTriangles& frame : history) {
        totals.push_back(frame.total());
    }
    return totals;
}

Result<std::vector<float>> RendererCore::readHdrImage() {
    if (!mTarget.hdr()) {
        return makeError(ErrorCode::InvalidArgument, "The render target has no HDR colour.");
    }
    return gpu::readTextureRgba16Float(*mContext, mTarget.sceneTexture());
}

wgpu::Texture RendererCore::passTexture(PassImage image) const {
    return mPassTargets ? mPassTargets->texture(image) : wgpu::Texture();
}

wgpu::TextureView RendererCore::passBytesView(PassImage image) const {
    return mPassTargets ? mPassTargets->bytesView(image) : wgpu::TextureView();
}

Result<image::ImageRgba8> RendererCore::readImage() {
    auto image = gpu::readTexture(*mContext, mTarget.colorTexture());
    if (!image) {
        // A lost device fails the read back; say so rather than how mapping failed.
        ENCORE_TRY(mContext->checkNoErrors("Rendering"));
        return image.error();
    }
    ENCORE_TRY(mContext->checkNoErrors("Rendering"));
    return image;
}

}  // namespace encore::render
