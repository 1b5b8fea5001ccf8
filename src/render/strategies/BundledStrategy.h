#pragma once

#include <memory>

#include "render/BundleRecorder.h"
#include "render/FramePasses.h"
#include "render/Strategy.h"

namespace encore::render {

// Any strategy whose recording does not depend on the camera (naive, layouts, pipeline-cache,
// instancing), recorded once into a render bundle and replayed with executeBundles: the
// bundling axis for the strategies that have no bundled form of their own. The wrapped strategy
// reads transforms from buffers (node uniforms, the GPU scene's instances), so updates leave the
// bundle valid; a replaced bind group of the GPU scene records it again.
class BundledStrategy final : public Strategy, public FramePasses {
  public:
    explicit BundledStrategy(std::unique_ptr<Strategy> recorded);

    StrategyKind kind() const override { return mRecorded->kind(); }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    Result<void> refresh() override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    void instanceMoved(std::size_t instance, const glm::mat4& world) override;
    InstanceTransformTargets instanceTransformTargets() const override;
    // The wrapped strategy's, with this strategy's bundles.
    StrategyReport report() const override;
    // Of the wrapped strategy's other passes, the bundled frame draws transmission alone (its
    // transmissive surfaces, recorded into a second bundle with the first), and checks the
    // target as it does.
    FramePasses* framePasses() override { return this; }
    bool drawsTransmission() const override;
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override;
    Result<void> checkTarget(std::uint32_t width, std::uint32_t height) const override;

  private:
    std::unique_ptr<Strategy> mRecorded;
    const RenderSetup* mSetup = nullptr;
    const GpuScene* mScene = nullptr;
    RecordedBundle mBundle;
    RecordedBundle mTransmission;  // Empty unless the wrapped strategy draws transmission.
    std::uint64_t mGeneration = 0;
    bool mStale = true;
    std::uint64_t mRecordings = 0;
};

}  // namespace encore::render
