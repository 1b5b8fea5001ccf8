#include "render/strategies/MaterialsStrategy.h"

#include <chrono>

#include "core/Elapsed.h"

namespace encore::render {

Result<void> MaterialsStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    const auto start = std::chrono::steady_clock::now();
    auto grouped = mDraws.prepare(setup, scene);
    setup.prepareTimes.draws += millisecondsSince(start);
    return grouped;
}

Result<void> MaterialsStrategy::refresh() {
    return mDraws.stale() ? mDraws.regroup() : Result<void>{};
}

void MaterialsStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    mDraws.setSharedBindGroups(encoder);
    mDraws.encodeOpaque(encoder);
    mDraws.encodeBlended(encoder, mDraws.blendOrder(frame.camera.position));
}

InstanceTransformTargets MaterialsStrategy::instanceTransformTargets() const {
    return mDraws.scene().instances().transformTargets();
}

}  // namespace encore::render
