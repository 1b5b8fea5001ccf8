#pragma once

#include "render/FramePasses.h"
#include "render/Strategy.h"
#include "render/strategies/MaterialDrawGroups.h"

namespace encore::render {

// The case study's Part 5: glTF materials (base colour factor and texture with its sampler,
// vertex colours, alpha MASK and BLEND, double-sided culling), shader variants only where the
// vertex inputs or the discard differ, one bind group per material. Opaque and masked geometry
// is drawn pipeline -> material -> primitive, so each material's bind group is set once per
// pipeline that uses it; blended geometry follows, one draw per instance, back to front
// (MaterialDrawGroups), recorded directly every frame.
class MaterialsStrategy final : public Strategy, public FramePasses {
  public:
    StrategyKind kind() const override { return StrategyKind::Materials; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    Result<void> refresh() override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override;

    FramePasses* framePasses() override { return this; }
    bool drawsTransmission() const override { return !mDraws.transmissive().empty(); }
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override;

  private:
    MaterialDrawGroups mDraws;
};

}  // namespace encore::render
