// RendererCore's animation: CPU evaluation through the player and instance updates, or GPU
// evaluation (GpuAnimation) whose compute passes the next frame records; switching between the
// two, and what of the playback survives a new player (encore/render/Renderer.h states the
// contract).

#include "render/renderer/RendererCore.h"

#include "gpu/OutOfMemoryScope.h"
#include "render/GpuScene.h"

namespace encore::render {

Result<void> RendererCore::createGpuAnimation() {
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    if (!mGpuScene || !mScene) {
        return {};
    }
    const std::string what = "Preparing GPU animation of '" + mScene->sourcePath.string() + "'";
    gpu::OutOfMemoryScope outOfMemory(*mContext);
    auto created = GpuAnimation::create(mContext->device(), mContext->queue(), *mShaders,
                                        mSetup->limits, *mScene, mGpuScene->animation(),
                                        mGpuScene->instances().transformTargets());
    ENCORE_TRY(outOfMemory.finish(what));
    if (!created) {
        return created.error().withContext(what);
    }
    ENCORE_TRY(mContext->checkNoErrors(what));
    mGpuAnimation = std::move(*created);
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
        if (mStrategy) {
            mGpuAnimation->copyInstancesTo(mStrategy->instanceTransformTargets().uniforms);
        }
    }
    return {};
}

Result<void> RendererCore::setAnimationEvaluation(AnimationEvaluation evaluation) {
    if (evaluation == mOptions.animation) {
        return {};
    }
    mOptions.animation = evaluation;
    if (!mStrategy) {
        return {};
    }
    if (evaluation == AnimationEvaluation::Gpu) {
        if (auto fits = GpuAnimation::checkLimits(mSetup->limits, *mScene); !fits) {
            mOptions.animation = AnimationEvaluation::Cpu;
            return fits.error().withContext("Switching '" + mScene->sourcePath.string() +
                                            "' to GPU animation");
        }
        return createGpuAnimation();
    }
    // Back to the CPU: a fresh player reports every instance, joint and weight as changed at
    // its first evaluate(), so everything the GPU wrote is overwritten.
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    const Playback playing = playback();
    mPlayer = std::make_unique<scene::AnimationPlayer>(*mScene);
    return restorePlayback(playing);
}

Result<void> RendererCore::selectAnimation(std::string_view nameOrIndex) {
    if (!mPlayer) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    if (nameOrIndex.empty()) {
        mPlayer->selectAll();
    } else {
        ENCORE_TRY(mPlayer->select(nameOrIndex));
    }
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
    }
    return {};
}

Result<void> RendererCore::setAnimationTime(double seconds) {
    if (!mStrategy || !mPlayer) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    mAnimationTime = seconds;
    if (mOptions.animation == AnimationEvaluation::Gpu) {
        AnimationFrameStats stats;
        stats.evaluation = AnimationEvaluation::Gpu;
        if (mGpuAnimation) {
            mGpuAnimation->setTime(mContext->queue(), seconds, mPlayer->mode());
            mGpuAnimationPending = true;
            stats.gpu = mGpuAnimation->stats();
            stats.bytesWritten = stats.gpu.bytesPerFrame;
        }
        mAnimationStats = stats;
        return {};
    }
    mPlayer->evaluate(seconds);
    AnimationFrameStats stats;
    stats.player = mPlayer->stats();
    const auto worlds = mPlayer->instanceWorlds();
    for (std::uint32_t instance : mPlayer->changedInstances()) {
        ENCORE_TRY(mGpuScene->updateInstance(instance, worlds[instance]));
        mStrategy->instanceMoved(instance, worlds[instance]);
        ++stats.instancesWritten;
    }
    stats.bytesWritten = std::uint64_t(stats.instancesWritten) * sizeof(TransformUniform);
    stats.upload = mGpuScene->writeAnimation(*mPlayer);
    stats.bytesWritten += stats.upload.bytesWritten;
    mAnimationStats = stats;
    return {};
}

void RendererCore::setPlaybackMode(scene::PlaybackMode mode) {
    mPlaybackMode = mode;
    if (mPlayer) {
        mPlayer->setMode(mode);
    }
}

RendererCore::Playback RendererCore::playback() const {
    if (!mPlayer) {
        return {};
    }
    return {{mPlayer->selection().begin(), mPlayer->selection().end()}, mPlayer->mode()};
}

Result<void> RendererCore::restorePlayback(const Playback& playback) {
    mPlayer->setMode(playback.mode);
    ENCORE_TRY(mPlayer->select(playback.selection));
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
    }
    return {};
}

const AnimationBuffers* RendererCore::animationBuffers() const {
    return mGpuScene ? mGpuScene->animation() : nullptr;
}

}  // namespace encore::render
