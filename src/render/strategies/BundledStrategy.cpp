#include "render/strategies/BundledStrategy.h"

#include "render/GpuScene.h"

namespace encore::render {

BundledStrategy::BundledStrategy(std::unique_ptr<Strategy> recorded)
    : mRecorded(std::move(recorded)) {}

Result<void> BundledStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    mSetup = &setup;
    mScene = &scene;
    mStale = true;
    return mRecorded->prepare(setup, scene);
}

Result<void> BundledStrategy::refresh() {
    return mRecorded->refresh();
}

void BundledStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    mRecorded->beforePass(commands, frame);
    // A replaced bind group of the GPU scene may be one the bundle holds.
    if (mStale || mGeneration != mScene->generation()) {
        // The wrapped strategies read nothing of the frame while recording (the camera comes
        // from the frame uniforms), so one recording serves every later frame.
        mBundle = recordBundle(*mSetup, "encore " + std::string(strategyName(kind())) + " frame",
                               [&](RenderEncoder& encoder) { mRecorded->encode(encoder, frame); });
        ++mRecordings;
        mTransmission = {};
        if (drawsTransmission()) {
            mTransmission = recordBundle(
                *mSetup, "encore " + std::string(strategyName(kind())) + " transmission",
                [&](RenderEncoder& encoder) {
                    mRecorded->framePasses()->encodeTransmission(encoder, frame);
                });
            ++mRecordings;
        }
        mStale = false;
        mGeneration = mScene->generation();
    }
}

void BundledStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.executeBundles(std::span(&mBundle.bundle, 1));
}

bool BundledStrategy::drawsTransmission() const {
    const FramePasses* passes = mRecorded->framePasses();
    return passes && passes->drawsTransmission();
}

void BundledStrategy::encodeTransmission(RenderEncoder& encoder, const FrameState&) const {
    encoder.executeBundles(std::span(&mTransmission.bundle, 1));
}

void BundledStrategy::instanceMoved(std::size_t instance, const glm::mat4& world) {
    mRecorded->instanceMoved(instance, world);
}

InstanceTransformTargets BundledStrategy::instanceTransformTargets() const {
    return mRecorded->instanceTransformTargets();
}

StrategyReport BundledStrategy::report() const {
    StrategyReport report = mRecorded->report();
    report.bundleContents = mBundle.contents;
    report.bundleContents += mTransmission.contents;
    report.bundlesRecorded = mRecordings;
    return report;
}

Result<void> BundledStrategy::checkTarget(std::uint32_t width, std::uint32_t height) const {
    const FramePasses* passes = mRecorded->framePasses();
    return passes ? passes->checkTarget(width, height) : Result<void>{};
}

}  // namespace encore::render
