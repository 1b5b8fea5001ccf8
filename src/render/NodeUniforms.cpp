#include "render/NodeUniforms.h"

#include <string>

#include "gpu/BindingResource.h"
#include "gpu/Upload.h"
#include "render/TransformData.h"

namespace encore::render {

NodeUniforms::NodeUniforms(const wgpu::Device& device,
                           const wgpu::Queue& queue,
                           const BindGroupLayouts& layouts,
                           const scene::SceneData& scene,
                           std::span<const glm::mat4> worlds) {
    mBuffers.reserve(scene.instances.size());
    mBindGroups.reserve(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& instance = scene.instances[i];
        // writeBuffer, not mappedAtCreation: Dawn gives every mapped-at-creation buffer that
        // the GPU cannot map its own staging allocation, which made 40,000 nodes take minutes
        // to prepare on an NVIDIA driver; writes share one staging ring.
        mBuffers.push_back(
            gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                              sizeof(TransformUniform), "node transform"));
        // Edited since loading: the normal matrix is computed again (the ids stay).
        scene::Instance placed = instance;
        if (worlds[i] != instance.world) {
            placed.world = worlds[i];
            placed.normalMatrix = normalMatrixOf(worlds[i]);
        }
        const TransformUniform transform = makeTransformUniform(placed);
        queue.WriteBuffer(mBuffers.back(), 0, &transform, sizeof(transform));
        mBindGroups.push_back(gpu::makeBindGroup(
            device, layouts.nodeUniform, {{0, mBuffers.back(), 0, sizeof(TransformUniform)}}));
    }
}

Result<void> NodeUniforms::checkLimit(const scene::SceneData& scene,
                                      std::optional<std::uint64_t> mappingBudget,
                                      std::string_view strategy) {
    constexpr std::uint64_t kMappingsPerNode = 2;  // Its uniform buffer and its bind group.
    if (mappingBudget && scene.instances.size() * kMappingsPerNode > *mappingBudget) {
        return makeError(
            ErrorCode::Unsupported,
            "The scene has " + std::to_string(scene.instances.size()) +
                " mesh nodes and strategy " + std::string(strategy) +
                " creates a uniform buffer and a bind group for each; this driver (lavapipe) maps "
                "memory for each and would crash at the kernel's limit (room for " +
                std::to_string(*mappingBudget / kMappingsPerNode) +
                " nodes; raise it with sysctl -w vm.max_map_count=262144). Use instancing or a "
                "later strategy for this scene.");
    }
    return {};
}

void NodeUniforms::update(const wgpu::Queue& queue,
                          std::size_t sceneInstance,
                          const glm::mat4& world) const {
    const TransformUniform transform = makeTransformUniform(world);
    queue.WriteBuffer(mBuffers[sceneInstance], 0, &transform, kTransformMatricesSize);
}

}  // namespace encore::render
