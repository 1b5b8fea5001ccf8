#pragma once

#include <map>
#include <utility>

#include "render/FramePasses.h"
#include "render/Strategy.h"
#include "render/culling/GpuCuller.h"
#include "render/strategies/BundledFrame.h"
#include "render/strategies/MaterialDrawGroups.h"

namespace encore::render {

// The `materials` frame with GPU culling (GpuCuller): compute passes bound every instance where
// this frame's transforms, joints and morph weights put it, test it against the frustum and,
// in frames of one view, against a depth pyramid of what was drawn first (two-phase occlusion
// culling), pick each primitive's level of detail, and write the instance counts of one indirect
// draw per (primitive, level, phase) and their visible-instance lists. Recorded directly each
// frame, or, with bundles, once into two render bundles (one per phase) whose draw sequence
// never changes (only the GPU-written counts do). Blended geometry is drawn as in `materials`,
// back to front, unculled, after both phases.
class GpuCullingStrategy final : public Strategy, public FramePasses {
  public:
    explicit GpuCullingStrategy(bool useBundles) : mUseBundles(useBundles) {}

    StrategyKind kind() const override {
        return mUseBundles ? StrategyKind::GpuCullingBundles : StrategyKind::GpuCulling;
    }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    Result<void> refresh() override;
    InstanceTransformTargets instanceTransformTargets() const override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    StrategyReport report() const override;

    FramePasses* framePasses() override { return this; }
    bool drawsInTwoPhases(const FrameState& frame) const override;
    void betweenPhases(const wgpu::CommandEncoder& commands,
                       const FrameState& frame,
                       const wgpu::Texture& depth) override;
    // Transmissive surfaces are not culled: they are drawn as `materials` draws them (from a
    // bundle of their own with bundles), after the copy.
    bool drawsTransmission() const override { return !mDraws.transmissive().empty(); }
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override;

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

    using PrimitiveDraw = MaterialDrawGroups::PrimitiveDraw;
    // The culler's draws, by (bindings, first instance slot).
    using DrawIndices = std::map<std::pair<const PrimitiveBindings*, std::uint32_t>, std::size_t>;

    // Groups the draws as `materials` does, each one an indirect draw of the culled variant.
    Result<void> groupDraws();
    // Every level's indirect draw of every culled primitive, with the arguments of `phase`.
    void encodeCulled(RenderEncoder& encoder, std::uint32_t phase) const;
    CulledDraw culledDraw(const PrimitiveDraw& primitive) const;
    // Whether the opaque draws grouped now are exactly the culler's.
    bool sameDraws(const DrawIndices& drawOf) const;

    bool mUseBundles;
    const RenderSetup* mSetup = nullptr;
    MaterialDrawGroups mDraws;
    bool mCullerCreated = false;
    std::vector<CulledPipeline> mCulled;
    GpuCuller mCuller;
    BundledFrame mFirstPhaseBundle;  // Phase 1's draws.
    BundledFrame mBundles;           // Phase 2's draws, then the blended geometry.
    BundledFrame mTransmission;      // The transmissive surfaces (transmission pass).
};

}  // namespace encore::render
