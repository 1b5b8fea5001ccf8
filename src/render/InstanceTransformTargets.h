#pragma once

// Where the world and normal matrices of the scene's instances live (TransformUniform, 128 bytes
// each), so that GPU-evaluated animation (GpuAnimation) can write them in place.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

namespace encore::render {

struct InstanceTransformTargets {
    // The GPU scene's instance buffer (what instancing and later strategies draw with): one
    // buffer with Storage usage, scene instance i at TransformUniform index slots[i].
    wgpu::Buffer storage;
    std::vector<std::uint32_t> slots;
    // Node-uniform strategies (naive, layouts, pipeline-cache): one uniform buffer with CopyDst
    // usage per scene instance, its transform at offset 0. Compute passes cannot write uniform
    // buffers, so GpuAnimation writes the GPU scene's instance buffer and copies from there.
    std::vector<wgpu::Buffer> uniforms;
};

}  // namespace encore::render
