#pragma once

#include <vector>

#include "encore/render/NodeUniforms.h"
#include "encore/render/Strategy.h"

namespace encore::render {

// The case study's Part 1, made to draw every model: one render pipeline per primitive; one
// uniform buffer and bind group per mesh node; every attribute accessor copied into its own
// tightly packed vertex buffer (so no accessor offset ever reaches a pipeline layout) and bound
// to its own slot. Loop: node -> primitive.
class NaiveStrategy final : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Naive; }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world) override;

  private:
    struct PreparedPrimitive {
        wgpu::RenderPipeline pipeline;
        std::vector<wgpu::Buffer> vertexBuffers;  // Slot i holds buffer i.
        wgpu::Buffer indexBuffer;
        wgpu::IndexFormat indexFormat = wgpu::IndexFormat::Undefined;
        std::uint32_t count = 0;  // Indices, or vertices when not indexed.
        scene::Topology topology = scene::Topology::TriangleList;
    };

    wgpu::BindGroup mFrameGroup;
    std::vector<std::vector<PreparedPrimitive>> mMeshes;
    std::vector<std::size_t> mNodeMeshes;  // Per scene instance.
    NodeUniforms mNodes;
    wgpu::Queue mQueue;
};

}  // namespace encore::render
