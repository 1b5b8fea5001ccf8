#include "render/strategies/BundlesStrategy.h"

namespace encore::render {

Result<void> BundlesStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    mSetup = &setup;
    mBundles = BundledFrame();
    mTransmission = BundledFrame();
    return mDraws.prepare(setup, scene);
}

Result<void> BundlesStrategy::refresh() {
    return mDraws.refresh();
}

void BundlesStrategy::beforePass(const wgpu::CommandEncoder&, const FrameState& frame) {
    mBundles.update(
        *mSetup, mDraws.scene().generation(), mDraws.blendOrder(frame.camera.position),
        [this](RenderEncoder& encoder) {
            mDraws.setSharedBindGroups(encoder);
            mDraws.encodeOpaque(encoder);
        },
        [this](RenderEncoder& encoder, std::span<const std::uint32_t> order) {
            mDraws.setSharedBindGroups(encoder);
            mDraws.encodeBlended(encoder, order);
        });
    if (drawsTransmission()) {
        mDraws.updateTransmissionBundle(mTransmission, *mSetup);
    }
}

void BundlesStrategy::encodeTransmission(RenderEncoder& encoder, const FrameState&) const {
    mTransmission.execute(encoder);
}

void BundlesStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    mBundles.execute(encoder);
}

InstanceTransformTargets BundlesStrategy::instanceTransformTargets() const {
    return mDraws.scene().instances().transformTargets();
}

}  // namespace encore::render
