#pragma once

#include <memory>

#include "render/BundleRecorder.h"
#include "render/Strategy.h"

namespace encore::render {

// Any strategy whose recording does not depend on the camera (naive, layouts, pipeline-cache,
// instancing), recorded once into a render bundle and replayed with executeBundles: the
// bundling axis for the strategies that have no bundled form of their own. The wrapped strategy
// reads transforms from buffers (node uniforms, the GPU scene's instances), so updates leave the
// bundle valid; a replaced bind group of the GPU scene records it again.
class BundledStrategy final : public Strategy {
  public:
    explicit BundledStrategy(std::unique_ptr<Strategy> recorded);

    StrategyKind kind() const override { return mRecorded->kind(); }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    Result<void> refresh() override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    // The wrapped strategy's transmissive surfaces, recorded into a second bundle with the first.
    bool drawsTransmission() const override { return mRecorded->drawsTransmission(); }
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override;
    void instanceMoved(std::size_t instance, const glm::mat4& world) override;
    InstanceTransformTargets instanceTransformTargets() const override;
    DrawCounters bundleContents() const override {
        DrawCounters contents = mBundle.contents;
        contents += mTransmission.contents;
        return contents;
    }
    std::uint64_t bundlesRecorded() const override { return mRecordings; }
    const GpuCuller* culler() const override { return mRecorded->culler(); }
    Result<void> checkTarget(std::uint32_t width, std::uint32_t height) const override {
        return mRecorded->checkTarget(width, height);
    }
    std::optional<GpuTriangleCounts> gpuTriangleCounts() const override {
        return mRecorded->gpuTriangleCounts();
    }

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
