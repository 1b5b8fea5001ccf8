#include "BundlesStrategy.h"

namespace encore::render {

Result<void> BundlesStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    ENCORE_TRY(MaterialsStrategy::prepare(setup, scene));
    mOpaque = {};
    mBlended = {};
    mRecordedBlendOrder.clear();
    mBundlesRecorded = 0;
    mStale = true;
    return {};
}

void BundlesStrategy::beforePass(const wgpu::CommandEncoder&, const FrameState& frame) {
    // A replaced bind group invalidates every bundle that bound the old one.
    if (mMaterials->generation() != mRecordedGeneration) {
        mStale = true;
    }
    if (mStale) {
        mOpaque = recordBundle(*mSetup, "encore opaque and masked geometry",
                               [this](RenderEncoder& encoder) {
                                   setSharedBindGroups(encoder);
                                   encodeOpaque(encoder);
                               });
        ++mBundlesRecorded;
    }
    // Blended geometry is sorted by distance: its bundle changes only with the order.
    auto order = blendOrder(frame.camera.position);
    if (!order.empty() && (mStale || order != mRecordedBlendOrder)) {
        mBlended = recordBundle(*mSetup, "encore blended geometry (back to front)",
                                [this, &order](RenderEncoder& encoder) {
                                    setSharedBindGroups(encoder);
                                    encodeBlended(encoder, order);
                                });
        mRecordedBlendOrder = std::move(order);
        ++mBundlesRecorded;
    }
    mRecordedGeneration = mMaterials->generation();
    mStale = false;
}

void BundlesStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    if (mBlended.bundle) {
        const wgpu::RenderBundle bundles[] = {mOpaque.bundle, mBlended.bundle};
        encoder.executeBundles(bundles);
    } else {
        encoder.executeBundles(std::span(&mOpaque.bundle, 1));
    }
}

DrawCounters BundlesStrategy::bundleContents() const {
    DrawCounters contents = mOpaque.contents;
    contents += mBlended.contents;
    return contents;
}

}  // namespace encore::render
