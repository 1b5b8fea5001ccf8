#include "render/InstanceBuffer.h"

#include <algorithm>

#include "gpu/BindingResource.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/TransformData.h"

namespace encore::render {

bool isMirrored(const glm::mat4& world) {
    return glm::determinant(glm::mat3(world)) < 0.0f;
}

namespace {

// Counting sort by (mesh, mirrored): stable, linear in the instance count.
std::vector<std::uint32_t> countInstances(const scene::SceneData& scene,
                                          std::vector<std::uint8_t>& mirrored) {
    std::vector<std::uint32_t> counts(scene.meshes.size() * 2, 0);
    mirrored.resize(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        mirrored[i] = isMirrored(scene.instances[i].world);
        ++counts[scene.instances[i].mesh.index() * 2 + mirrored[i]];
    }
    return counts;
}

}  // namespace

std::vector<std::uint32_t> instanceSlots(const scene::SceneData& scene) {
    std::vector<std::uint8_t> mirrored;
    std::vector<std::uint32_t> cursor = countInstances(scene, mirrored);
    std::uint32_t next = 0;
    for (std::uint32_t& count : cursor) {  // Counts become each (mesh, mirrored) first slot.
        const std::uint32_t first = next;
        next += count;
        count = first;
    }
    std::vector<std::uint32_t> slots(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        slots[i] = cursor[scene.instances[i].mesh.index() * 2 + mirrored[i]]++;
    }
    return slots;
}

InstanceBuffer::InstanceBuffer(const wgpu::Device& device,
                               const BindGroupLayouts& layouts,
                               const scene::SceneData& scene,
                               gpu::ResourcePool* pool) {
    const std::size_t meshCount = scene.meshes.size();
    std::vector<std::uint8_t> mirrored;
    const std::vector<std::uint32_t> counts = countInstances(scene, mirrored);
    mRegular.resize(meshCount);
    mMirrored.resize(meshCount);
    std::uint32_t next = 0;
    for (std::size_t mesh = 0; mesh < meshCount; ++mesh) {
        mRegular[mesh] = {next, counts[mesh * 2]};
        next += counts[mesh * 2];
        mMirrored[mesh] = {next, counts[mesh * 2 + 1]};
        next += counts[mesh * 2 + 1];
    }
    mSlots = instanceSlots(scene);
    mInstances.resize(scene.instances.size());
    std::vector<TransformUniform> transforms(std::max<std::size_t>(scene.instances.size(), 1));
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const std::uint32_t slot = mSlots[i];
        mInstances[slot] = i;
        transforms[slot] = makeTransformUniform(scene.instances[i]);
    }
    const wgpu::BufferUsage usage =
        wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc;
    mBuffer = gpu::bufferWithData(pool, device, device.GetQueue(), usage,
                                  {reinterpret_cast<const std::uint8_t*>(transforms.data()),
                                   transforms.size() * sizeof(TransformUniform)},
                                  "instance transforms");

    mBindGroup = gpu::makeBindGroup(device, layouts.instanceStorage,
                                    {{0, mBuffer, 0, mBuffer.GetSize()}}, "instance transforms");
}

void InstanceBuffer::giveBackTo(gpu::ResourcePool& pool) {
    mBindGroup = nullptr;
    pool.giveBack(std::move(mBuffer));
}

InstanceRange InstanceBuffer::meshRange(scene::MeshId mesh) const {
    const InstanceRange& regular = mRegular[mesh.index()];
    return {regular.first, regular.count + mMirrored[mesh.index()].count};
}

InstanceRange InstanceBuffer::meshRange(scene::MeshId mesh, bool mirrored) const {
    return mirrored ? mMirrored[mesh.index()] : mRegular[mesh.index()];
}

void InstanceBuffer::update(const wgpu::Queue& queue,
                            std::size_t sceneInstance,
                            const glm::mat4& world) const {
    const TransformUniform transform = makeTransformUniform(world);
    queue.WriteBuffer(mBuffer, std::uint64_t(mSlots[sceneInstance]) * sizeof(TransformUniform),
                      &transform, kTransformMatricesSize);
}

}  // namespace encore::render
