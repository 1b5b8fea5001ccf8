#include "encore/render/NodeUniforms.h"

#include "encore/gpu/Upload.h"
#include "encore/render/TransformData.h"

namespace encore::render {

NodeUniforms::NodeUniforms(const wgpu::Device& device, const BindGroupLayouts& layouts,
                           const scene::SceneData& scene) {
    mBuffers.reserve(scene.instances.size());
    mBindGroups.reserve(scene.instances.size());
    for (const scene::Instance& instance : scene.instances) {
        const TransformUniform transform = makeTransformUniform(instance);
        mBuffers.push_back(gpu::createBufferWithData(
            device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
            std::span(reinterpret_cast<const std::uint8_t*>(&transform), sizeof(transform)),
            "node transform"));
        wgpu::BindGroupEntry entry{};
        entry.binding = 0;
        entry.buffer = mBuffers.back();
        entry.size = sizeof(TransformUniform);
        wgpu::BindGroupDescriptor descriptor{};
        descriptor.layout = layouts.nodeUniform;
        descriptor.entryCount = 1;
        descriptor.entries = &entry;
        mBindGroups.push_back(device.CreateBindGroup(&descriptor));
    }
}

void NodeUniforms::update(const wgpu::Queue& queue, std::size_t sceneInstance,
                          const glm::mat4& world) const {
    const TransformUniform transform = makeTransformUniform(world);
    queue.WriteBuffer(mBuffers[sceneInstance], 0, &transform, sizeof(transform));
}

}  // namespace encore::render
