#pragma once

// Where a strategy keeps the world and normal matrices of the scene's instances (TransformUniform,
// 128 bytes each), so that GPU-evaluated animation (GpuAnimation) can write them in place.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

namespace encore::render {

struct InstanceTransformTargets {
    // Instance-storage strategies (instancing and later): one buffer with Storage usage, scene
    // instance i at TransformUniform index slots[i].
    wgpu::Buffer storage;
    std::vector<std::uint32_t> slots;
    // Node-uniform strategies (naive, layouts, pipeline-cache): one uniform buffer with CopyDst
    // usage per scene instance, its transform at offset 0. Compute passes cannot write uniform
    // buffers, so GpuAnimation computes into a buffer of its own and copies.
    std::vector<wgpu::Buffer> uniforms;
};

}  // namespace encore::render
