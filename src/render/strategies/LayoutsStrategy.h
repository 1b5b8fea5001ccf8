#pragma once

#include <memory>
#include <vector>

#include "encore/render/NodeUniforms.h"
#include "encore/render/Strategy.h"
#include "encore/render/VertexBindings.h"

namespace encore::render {

// The case study's Part 2: vertex data bound where it lies (one buffer per bufferView, offsets
// moved into setVertexBuffer, interleaved attributes in one slot), still one pipeline per
// primitive and the node -> primitive loop of `naive`.
class LayoutsStrategy final : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Layouts; }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world) override;

  private:
    struct PreparedPrimitive {
        wgpu::RenderPipeline pipeline;
        PrimitiveBindings bindings;
    };

    std::unique_ptr<GeometryBuffers> mGeometry;
    wgpu::BindGroup mFrameGroup;
    std::vector<std::vector<PreparedPrimitive>> mMeshes;
    std::vector<std::size_t> mNodeMeshes;
    NodeUniforms mNodes;
    wgpu::Queue mQueue;
};

}  // namespace encore::render
