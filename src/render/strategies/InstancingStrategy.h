#pragma once

#include <memory>
#include <vector>

#include "encore/render/InstanceBuffer.h"
#include "encore/render/PipelineCache.h"
#include "encore/render/Strategy.h"
#include "encore/render/VertexBindings.h"

namespace encore::render {

// The case study's Part 4: all transforms in one storage buffer bound once; each primitive drawn
// once for all the instances of its mesh (firstInstance selects them). Loop pipeline ->
// primitive.
class InstancingStrategy final : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Instancing; }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mInstances.transformTargets();
    }
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world) override;


    const InstanceBuffer& instances() const { return mInstances; }

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

    std::unique_ptr<GeometryBuffers> mGeometry;
    std::unique_ptr<PipelineCache> mOwnPipelines;
    PipelineCache* mPipelines = nullptr;  // mOwnPipelines or the renderer's kept cache.
    wgpu::BindGroup mFrameGroup;
    InstanceBuffer mInstances;
    wgpu::Queue mQueue;
    std::vector<PipelineGroup> mGroups;
    const AnimationBuffers* mAnimation = nullptr;
};

}  // namespace encore::render
