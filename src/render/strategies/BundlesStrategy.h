#pragma once

#include "render/FramePasses.h"
#include "render/Strategy.h"
#include "render/strategies/BundledFrame.h"
#include "render/strategies/MaterialDrawGroups.h"

namespace encore::render {

// The `materials` frame recorded once into a render bundle and replayed every frame with
// executeBundles. The camera, transforms and material factors change through buffers, so the
// opaque bundle is never re-recorded for them. Blended geometry lives in a second bundle that is
// re-recorded only when the back-to-front order changes; both are re-recorded when a bind group
// they reference is replaced (the GPU scene's generation changes). Surfaces with
// KHR_materials_transmission are a third bundle, replayed in the transmission pass.
class BundlesStrategy final : public Strategy, public FramePasses {
  public:
    StrategyKind kind() const override { return StrategyKind::Bundles; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    Result<void> refresh() override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override;
    StrategyReport report() const override {
        StrategyReport report;
        report.bundleContents = mBundles.contents();
        report.bundleContents += mTransmission.contents();
        report.bundlesRecorded = mBundles.recorded() + mTransmission.recorded();
        return report;
    }

    FramePasses* framePasses() override { return this; }
    bool drawsTransmission() const override { return !mDraws.transmissive().empty(); }
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override;

  private:
    const RenderSetup* mSetup = nullptr;
    MaterialDrawGroups mDraws;
    BundledFrame mBundles;
    // The transmissive surfaces: one more bundle, recorded once like the opaque one.
    BundledFrame mTransmission;
};

}  // namespace encore::render
