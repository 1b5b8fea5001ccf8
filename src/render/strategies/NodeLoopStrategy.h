#pragma once

#include <vector>

#include "render/AnimationBuffers.h"
#include "render/GpuScene.h"
#include "render/NodeUniforms.h"
#include "render/Strategy.h"
#include "render/VertexBindings.h"

namespace encore::render {

// The frame of the case study's Parts 1 and 2: for each mesh node, its own bind group, then for
// each primitive of its mesh a pipeline, the vertex and index buffers and a draw. `naive` and
// `layouts` differ only in how they prepare each primitive's pipeline and bindings.
class NodeLoopStrategy : public Strategy {
  public:
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mNodes.transformTargets();
    }
    void instanceMoved(std::size_t instance, const glm::mat4& world) override;

  protected:
    struct PreparedPrimitive {
        wgpu::RenderPipeline pipeline;
        PrimitiveBindings bindings;
        shaders::ShaderVariantKey shader;  // Whether the animation group is bound.
    };

    // Checks the scene against the driver's budget; call first in prepare().
    Result<void> beginPrepare(const RenderSetup& setup, const GpuScene& scene);
    // Creates the per-node uniforms; call last in prepare(), once mMeshes is filled.
    void finishPrepare(const RenderSetup& setup, const GpuScene& scene);

    std::vector<std::vector<PreparedPrimitive>> mMeshes;  // Per mesh, per primitive.
    const AnimationBuffers* mAnimation = nullptr;

  private:
    wgpu::BindGroup mFrameGroup;
    std::vector<std::size_t> mNodeMeshes;  // Per scene instance.
    NodeUniforms mNodes;
    wgpu::Queue mQueue;
};

}  // namespace encore::render
