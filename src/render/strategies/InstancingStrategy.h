#pragma once

#include <memory>
#include <vector>

#include "render/GpuScene.h"
#include "render/InstanceBuffer.h"
#include "render/PipelineCache.h"
#include "render/Strategy.h"
#include "render/VertexBindings.h"

namespace encore::render {

// The case study's Part 4: all transforms in one storage buffer bound once; each primitive drawn
// once for all the instances of its mesh (firstInstance selects them). Loop pipeline ->
// primitive.
class InstancingStrategy final : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Instancing; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mScene->instances().transformTargets();
    }

  private:
    struct PrimitiveDraw {
        PrimitiveBindings bindings;
        InstanceRange instances;
        shaders::ShaderVariantKey shader;
        std::size_t sceneInstance = 0;  // The range's first instance, and the primitive's
        std::size_t primitive = 0;      // index in its mesh: its animation draw record.
    };
    struct PipelineGroup {
        wgpu::RenderPipeline pipeline;
        std::vector<PrimitiveDraw> primitives;
    };

    const GpuScene* mScene = nullptr;
    std::unique_ptr<PipelineCache> mOwnPipelines;
    PipelineCache* mPipelines = nullptr;  // mOwnPipelines or the renderer's kept cache.
    wgpu::BindGroup mFrameGroup;
    std::vector<PipelineGroup> mGroups;
};

}  // namespace encore::render
