// Renderer's frames: the frame uniforms, one render pass per view (or the two passes of a
// two-phase frame) recorded by the strategy, with transmissive surfaces the copy and one
// transmission pass per view (TransmissionPass.h), tone mapping, timing and submission; then
// the triangle counts of GPU culling and the image read back.

#include "encore/render/Renderer.h"

#include <array>
#include <optional>
#include <span>

#include "gpu/Readback.h"
#include "gpu/TimedSubmit.h"
#include "render/PassAttachments.h"
#include "render/PassTargets.h"
#include "render/TransmissionPass.h"
#include "render/TriangleHistory.h"

namespace encore::render {

FrameResult Renderer::renderFrame(const Camera& camera,
                                  float timeSeconds,
                                  std::vector<RecordedCall>* trace) {
    return renderPasses(std::span(&camera, 1), timeSeconds, trace);
}

FrameResult Renderer::renderViews(std::span<const Camera> cameras, float timeSeconds) {
    return renderPasses(cameras, timeSeconds, nullptr);
}

const wgpu::PassTimestampWrites* Renderer::timestampWrites(GpuStage stage, std::string_view label) {
    if (mTimer) {
        return mTimer->nextPass(label);
    }
    return mStageTimestamps ? mStageTimestamps->pass(gpuStageIndex(stage)) : nullptr;
}

FrameResult Renderer::renderPasses(std::span<const Camera> cameras,
                                   float timeSeconds,
                                   std::vector<RecordedCall>* trace) {
    FrameResult result;
    if (cameras.empty()) {
        return result;
    }
    const bool multiView = cameras.size() > 1;
    if (multiView) {
        mFrame->writeViews(mContext->device(), mContext->queue(), cameras, timeSeconds);
    } else {
        mFrame->update(mContext->queue(), cameras[0], timeSeconds);
    }
    FrameState state{cameras[0], cameras, timeSeconds, mTimer, mCullingCamera};
    state.culling = mOptions.culling;
    state.targetWidth = mTarget.width();
    state.targetHeight = mTarget.height();
    state.transformsAnimated = mGpuAnimation && mGpuAnimationPending;
    const bool twoPhases = !multiView && mStrategy && mStrategy->drawsInTwoPhases(state);
    if (twoPhases) {
        state.phase = DrawPhase::First;
    }

    // Only scenes with transmissive surfaces pay for the copy and the extra passes.
    const bool transmission = mTransmission && mStrategy && mStrategy->drawsTransmission();
    // One scene pass, of colour alone: what a strategy may compose some other way.
    const bool singlePass = mStrategy && !twoPhases && !transmission && !mPassTargets;
    // Straight into the resolved texture at one sample (Strategy::composesResolved).
    const bool resolvedPasses = singlePass && mResolvedBackground && mStrategy->composesResolved();
    // Every pixel composed in compute (Strategy::composesFrame): no scene render pass at all.
    const bool composedFrame = singlePass &&
                               mOptions.toneMapping.background != BackgroundKind::Environment &&
                               mStrategy->composesFrame(state);
    std::optional<PassAttachments> composedAttachments;
    if (composedFrame) {
        PassPlan plan;
        plan.viewCount = cameras.size();
        plan.hdr = mTarget.hdr();
        plan.backgroundColor = mOptions.toneMapping.backgroundColor;
        composedAttachments = passAttachments(plan);
        state.composedBackground = composedAttachments->clearColor;
        state.composedView = mTarget.sceneStorageView();
    }
    auto encodeFrame = [&](const wgpu::CommandEncoder& commandEncoder) {
        if (mGpuAnimation && mGpuAnimationPending) {
            mGpuAnimation->encode(commandEncoder);  // Before anything that reads its results.
            mGpuAnimationPending = false;
        }
        if (mStrategy && mStageTimestamps) {
            mStageTimestamps->timeCommands(commandEncoder, gpuStageIndex(GpuStage::BeforePasses),
                                           [&] { mStrategy->beforePass(commandEncoder, state); });
        } else if (mStrategy) {
            mStrategy->beforePass(commandEncoder, state);
        }
        const std::uint32_t viewWidth = mTarget.width() / std::uint32_t(cameras.size());
        // One pass per view, or the two passes of a two-phase frame; what each loads, keeps and
        // resolves is passAttachments' decision (PassAttachments.h).
        auto encodePass = [&](std::size_t view, DrawPhase phase, bool transmissionPass) {
            PassPlan plan;
            plan.view = view;
            plan.viewCount = cameras.size();
            plan.phase = phase;
            plan.multisampled = mTarget.sampleCount() > 1 && !resolvedPasses;
            plan.hdr = mTarget.hdr();
            plan.backgroundColor = mOptions.toneMapping.backgroundColor;
            plan.transmission = transmissionPass;
            plan.transmissionFollows =
                transmission && !transmissionPass && phase != DrawPhase::First;
            const PassAttachments attachments = passAttachments(plan);
            wgpu::RenderPassColorAttachment color =
                resolvedPasses ? mTarget.resolvedColorAttachment(attachments.clearColor)
                               : mTarget.colorAttachment(attachments.clearColor);
            color.loadOp = attachments.colorLoadOp;
            color.storeOp = attachments.colorStoreOp;
            if (!attachments.resolve) {
                color.resolveTarget = nullptr;
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
                mPassTargets->fillAttachments(color,
                                              std::span(colors).subspan<1, kPassTargetCount>());
                colorCount += kPassTargetCount;
            }
            wgpu::RenderPassDescriptor passDescriptor{};
            passDescriptor.label = attachments.label;
            passDescriptor.colorAttachmentCount = colorCount;
            passDescriptor.colorAttachments = colors.data();
            passDescriptor.depthStencilAttachment = resolvedPasses ? nullptr : &depth;
            // The transmission pass is timed by the GPU timer only (stage timestamps time one
            // scene pass per view).
            passDescriptor.timestampWrites =
                transmissionPass ? (mTimer ? mTimer->nextPass(attachments.timestampLabel) : nullptr)
                                 : timestampWrites(GpuStage::Scene, attachments.timestampLabel);
            wgpu::RenderPassEncoder pass = commandEncoder.BeginRenderPass(&passDescriptor);
            if (multiView) {
                pass.SetViewport(float(view * viewWidth), 0.0f, float(viewWidth),
                                 float(mTarget.height()), 0.0f, 1.0f);
                // Clipping keeps a view's fragments inside its viewport already; the scissor makes
                // sure no rounding reaches the neighbouring strips, whose colour and depth persist.
                pass.SetScissorRect(view * viewWidth, 0, viewWidth, mTarget.height());
            }
            if (mOptions.toneMapping.background == BackgroundKind::Environment &&
                phase != DrawPhase::Second && !transmissionPass) {
                (resolvedPasses ? mResolvedBackground : mBackground)
                    ->draw(pass, mFrame->bindGroup());
            }
            if (mStrategy) {
                RenderEncoder encoder(pass, result.counters);
                encoder.setTrace(trace);
                FrameState viewState = state;
                viewState.camera = cameras[view];
                viewState.phase = phase;
                viewState.resolvedPass = resolvedPasses;
                if (transmissionPass) {
                    mStrategy->encodeTransmission(encoder, viewState);
                } else {
                    mStrategy->encode(encoder, viewState);
                }
            }
            pass.End();
        };
        if (composedAttachments) {
            FrameComposition composition;
            composition.background = composedAttachments->clearColor;
            composition.timestampWrites =
                timestampWrites(GpuStage::Scene, composedAttachments->timestampLabel);
            mStrategy->composeFrame(commandEncoder, state, composition);
        } else if (twoPhases) {
            encodePass(0, DrawPhase::First, false);
            mStrategy->betweenPhases(commandEncoder, state, mTarget.depthTexture());
            encodePass(0, DrawPhase::Second, false);
        } else {
            for (std::size_t view = 0; view < cameras.size(); ++view) {
                if (multiView) {
                    mFrame->selectView(commandEncoder, view);
                }
                encodePass(view, DrawPhase::Whole, false);
            }
        }
        if (transmission) {
            // Everything but the transmissive surfaces is drawn (and resolved): copy it once for
            // all views, then draw them over it view by view.
            mTransmission->encodeCopy(commandEncoder, mTarget.sceneView(), mTimer);
            ++result.transmissionCopies;
            for (std::size_t view = 0; view < cameras.size(); ++view) {
                if (multiView) {
                    mFrame->selectView(commandEncoder, view);
                }
                encodePass(view, twoPhases ? DrawPhase::Second : DrawPhase::Whole, true);
            }
        }
        // After the last pass: a two-phase frame counts in both culling passes.
        if (mTriangleHistory && mStrategy) {
            if (auto counts = mStrategy->gpuTriangleCounts()) {
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
    };
    const gpu::SubmitTiming timing = gpu::submitTimed(*mContext, mTimer, encodeFrame);
    result.encodeMilliseconds = timing.encodeMilliseconds;
    result.submitMilliseconds = timing.submitMilliseconds;
    result.gpuMilliseconds = timing.gpuMilliseconds;
    if (mStrategy) {
        result.bundleContents = mStrategy->bundleContents();
    }
    // Bundles and indirect draws replay per view; counters already sum the direct draws.
    const auto gpuCounts = mStrategy ? mStrategy->gpuTriangleCounts() : std::nullopt;
    result.trianglesSubmitted =
        result.counters.triangles + cameras.size() * (result.bundleContents.triangles +
                                                      (gpuCounts ? gpuCounts->candidates : 0));
    return result;
}

void Renderer::toneMapScene() {
    if (!mToneMapper) {
        return;
    }
    wgpu::CommandEncoder commands = mContext->device().CreateCommandEncoder();
    mToneMapper->encode(commands, mTarget);
    wgpu::CommandBuffer buffer = commands.Finish();
    mContext->queue().Submit(1, &buffer);
}

void Renderer::setTriangleCounting(bool on) {
    mTriangleHistory = on ? std::make_unique<TriangleHistory>(mContext->device()) : nullptr;
}

Result<std::vector<DrawnTriangles>> Renderer::takeTriangleHistory() {
    if (!mTriangleHistory) {
        return std::vector<DrawnTriangles>{};
    }
    return mTriangleHistory->take(*mContext);
}

Result<std::vector<std::uint64_t>> Renderer::takeDrawnTriangles() {
    ENCORE_TRY_ASSIGN(auto history, takeTriangleHistory());
    std::vector<std::uint64_t> totals;
    totals.reserve(history.size());
    for (const DrawnTriangles& frame : history) {
        totals.push_back(frame.total());
    }
    return totals;
}

Result<std::vector<float>> Renderer::readHdrImage() {
    if (!mTarget.hdr()) {
        return makeError(ErrorCode::InvalidArgument, "The render target has no HDR colour.");
    }
    return gpu::readTextureRgba16Float(*mContext, mTarget.sceneTexture());
}

wgpu::Texture Renderer::passTexture(PassImage image) const {
    return mPassTargets ? mPassTargets->texture(image) : wgpu::Texture();
}

wgpu::TextureView Renderer::passBytesView(PassImage image) const {
    return mPassTargets ? mPassTargets->bytesView(image) : wgpu::TextureView();
}

Result<image::ImageRgba8> Renderer::readImage() {
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
