#pragma once

#include <memory>
#include <vector>

#include "render/GpuScene.h"
#include "render/NodeUniforms.h"
#include "render/PipelineCache.h"
#include "render/Strategy.h"
#include "render/VertexBindings.h"

namespace encore::render {

// The case study's Part 3: pipelines cached by a key of every pipeline argument, and the frame
// regrouped pipeline -> primitive -> node, so setPipeline happens once per distinct pipeline and
// vertex buffers once per primitive.
class PipelineCacheStrategy final : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::PipelineCache; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mNodes.transformTargets();
    }
    void instanceMoved(std::size_t instance, const glm::mat4& world) override;

    std::size_t pipelineCount() const { return mPipelines ? mPipelines->size() : 0; }

  private:
    struct PrimitiveDraws {
        PrimitiveBindings bindings;
        std::vector<std::size_t> nodes;  // Scene instances drawing this primitive.
        shaders::ShaderVariantKey shader;
        std::size_t primitive = 0;  // Its index in the mesh (animation draw records).
    };
    struct PipelineGroup {
        wgpu::RenderPipeline pipeline;
        std::vector<PrimitiveDraws> primitives;
    };

    std::unique_ptr<PipelineCache> mPipelines;
    wgpu::BindGroup mFrameGroup;
    std::vector<PipelineGroup> mGroups;
    NodeUniforms mNodes;
    wgpu::Queue mQueue;
    const AnimationBuffers* mAnimation = nullptr;
};

}  // namespace encore::render
