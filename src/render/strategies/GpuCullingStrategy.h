#pragma once

#include "BundledFrame.h"
#include "MaterialsStrategy.h"
#include "encore/render/GpuCuller.h"

namespace encore::render {

// The `materials` frame with GPU frustum culling: a compute pass bounds every instance where
// this frame's transforms, joints and morph weights put it, tests it each frame and writes the instance counts of one indirect draw per (primitive, instance range) and
// their visible-instance lists. Recorded directly each frame, or, with bundles, once into a
// render bundle whose draw sequence never changes (only the GPU-written counts do). Blended
// geometry is drawn as in `materials`, back to front, unculled.
class GpuCullingStrategy final : public MaterialsStrategy {
  public:
    explicit GpuCullingStrategy(bool useBundles) : mUseBundles(useBundles) {}

    StrategyKind kind() const override {
        return mUseBundles ? StrategyKind::GpuCullingBundles : StrategyKind::GpuCulling;
    }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    DrawCounters bundleContents() const override { return mBundles.contents(); }
    std::uint64_t bundlesRecorded() const override { return mBundles.recorded(); }
    const GpuCuller* culler() const override { return &mCuller; }

  private:
    struct CulledPrimitive {
        const PrimitiveBindings* bindings = nullptr;
        std::uint32_t firstInstance = 0;  // With bindings, identifies the draw across groupings.
        std::size_t draw = 0;             // Index into the culler's draws.
        std::size_t sceneInstance = 0;    // Its animation draw record (animated variants).
        std::size_t primitive = 0;
    };
    struct CulledMaterial {
        scene::MaterialId material;
        std::vector<CulledPrimitive> primitives;
    };
    struct CulledPipeline {
        wgpu::RenderPipeline pipeline;
        shaders::ShaderVariantKey shader;
        std::vector<CulledMaterial> materials;
    };

    Result<void> groupDraws() override;
    void encodeCulled(RenderEncoder& encoder) const;

    bool mUseBundles;
    bool mCullerCreated = false;
    std::vector<CulledPipeline> mCulled;
    GpuCuller mCuller;
    BundledFrame mBundles;
};

}  // namespace encore::render
