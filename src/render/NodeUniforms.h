#pragma once

// The case study's Parts 1-3 per-node transforms: one uniform buffer and one bind group (group
// 1) per mesh node, in scene.instances order.

#include <webgpu/webgpu_cpp.h>

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"

#include "encore/scene/SceneData.h"
#include "render/BindGroupLayouts.h"
#include "render/InstanceTransformTargets.h"

namespace encore::render {

class NodeUniforms {
  public:
    NodeUniforms() = default;
    // One buffer per instance of `scene`, holding its transform in `worlds` (one per instance:
    // the GPU scene's, edits included).
    NodeUniforms(const wgpu::Device& device,
                 const wgpu::Queue& queue,
                 const BindGroupLayouts& layouts,
                 const scene::SceneData& scene,
                 std::span<const glm::mat4> worlds);

    // An error when the per-node buffers and bind groups (about two driver memory mappings
    // each on lavapipe) would exceed `mappingBudget` (gpu::Context::mappingBudget), naming the
    // strategy that would create them.
    static Result<void> checkLimit(const scene::SceneData& scene,
                                   std::optional<std::uint64_t> mappingBudget,
                                   std::string_view strategy);

    const wgpu::BindGroup& bindGroup(std::size_t sceneInstance) const {
        return mBindGroups[sceneInstance];
    }
    void update(const wgpu::Queue& queue, std::size_t sceneInstance, const glm::mat4& world) const;
    std::size_t size() const { return mBindGroups.size(); }
    // Where GpuAnimation copies animated instances (one uniform buffer per scene instance).
    InstanceTransformTargets transformTargets() const { return {{}, {}, mBuffers}; }

  private:
    std::vector<wgpu::Buffer> mBuffers;
    std::vector<wgpu::BindGroup> mBindGroups;
};

}  // namespace encore::render
