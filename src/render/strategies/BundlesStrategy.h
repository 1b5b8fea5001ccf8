#pragma once

#include "BundledFrame.h"
#include "MaterialsStrategy.h"

namespace encore::render {

// The `materials` frame recorded once into a render bundle and replayed every frame with
// executeBundles. The camera, transforms and material factors change through buffers, so the
// opaque bundle is never re-recorded for them. Blended geometry lives in a second bundle that is
// re-recorded only when the back-to-front order changes; both are re-recorded when a resource
// they reference is replaced (MaterialResources' generation changes).
class BundlesStrategy final : public MaterialsStrategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Bundles; }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    DrawCounters bundleContents() const override { return mBundles.contents(); }
    std::uint64_t bundlesRecorded() const override { return mBundles.recorded(); }

  private:
    BundledFrame mBundles;
};

}  // namespace encore::render
