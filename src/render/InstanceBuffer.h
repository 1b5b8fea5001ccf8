#pragma once

// The case study's Part 4: every instance transform (world + normal matrix) in one storage
// buffer, bound once as group 1 and indexed in the vertex shader by instance_index, which
// starts at the draw's firstInstance. Instances are ordered so that each mesh's instances are
// adjacent — first those with a regular transform, then mirrored ones (negative determinant,
// which flip the winding) — so one draw covers a mesh's primitive for all its instances.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/scene/SceneData.h"
#include "render/BindGroupLayouts.h"
#include "render/InstanceTransformTargets.h"

namespace encore::gpu {
class ResourcePool;
}

namespace encore::render {

struct InstanceRange {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

class InstanceBuffer {
  public:
    InstanceBuffer() = default;
    // `pool`: where the buffer comes from (gpu/ResourcePool.h); null: created.
    InstanceBuffer(const wgpu::Device& device,
                   const BindGroupLayouts& layouts,
                   const scene::SceneData& scene,
                   gpu::ResourcePool* pool = nullptr);
    // Hands the buffer to `pool` (the scene is being released: nothing binds it again).
    void giveBackTo(gpu::ResourcePool& pool);

    const wgpu::BindGroup& bindGroup() const { return mBindGroup; }
    const wgpu::Buffer& buffer() const { return mBuffer; }

    // All instances of a mesh, regular then mirrored.
    InstanceRange meshRange(scene::MeshId mesh) const;
    // Only the regular (mirrored = false) or only the mirrored instances of a mesh.
    InstanceRange meshRange(scene::MeshId mesh, bool mirrored) const;

    // The buffer slot of scene.instances[index].
    std::uint32_t slotOf(std::size_t sceneInstance) const { return mSlots[sceneInstance]; }
    // The scene instance stored in a slot.
    std::size_t instanceAt(std::uint32_t slot) const { return mInstances[slot]; }
    std::uint32_t size() const { return static_cast<std::uint32_t>(mInstances.size()); }
    // Where GpuAnimation writes animated instances (the buffer has Storage and CopySrc usage).
    InstanceTransformTargets transformTargets() const { return {mBuffer, mSlots, {}}; }

    // Rewrites one instance's transforms (animation, edits) without touching bind groups.
    void update(const wgpu::Queue& queue, std::size_t sceneInstance, const glm::mat4& world) const;

  private:
    wgpu::Buffer mBuffer;
    wgpu::BindGroup mBindGroup;
    std::vector<std::uint32_t> mSlots;     // Scene instance -> slot.
    std::vector<std::size_t> mInstances;   // Slot -> scene instance.
    std::vector<InstanceRange> mRegular;   // Per mesh.
    std::vector<InstanceRange> mMirrored;  // Per mesh.
};

// Whether a transform mirrors geometry (negative determinant of its 3x3 part).
bool isMirrored(const glm::mat4& world);

// The slot of each scene instance in an InstanceBuffer of `scene` (its mesh-major order), for
// per-instance arrays that must be indexed like the transforms (AnimationBuffers).
std::vector<std::uint32_t> instanceSlots(const scene::SceneData& scene);

}  // namespace encore::render
