#include "render/strategies/MaterialsStrategy.h"

namespace encore::render {

Result<void> MaterialsStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    return mDraws.prepare(setup, scene);
}

Result<void> MaterialsStrategy::refresh() {
    return mDraws.refresh();
}

void MaterialsStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    mDraws.setSharedBindGroups(encoder);
    mDraws.encodeOpaque(encoder);
    mDraws.encodeBlended(encoder, mDraws.blendOrder(frame.camera.position));
}

void MaterialsStrategy::encodeTransmission(RenderEncoder& encoder, const FrameState&) const {
    mDraws.setSharedBindGroups(encoder);
    mDraws.encodeTransmissive(encoder);
}

InstanceTransformTargets MaterialsStrategy::instanceTransformTargets() const {
    return mDraws.scene().instances().transformTargets();
}

}  // namespace encore::render
