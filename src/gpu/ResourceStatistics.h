#pragma once

// What a device holds, for soak tests and diagnostics. Counted by Dawn itself (its memory dump,
// dawn::native::DumpMemoryStatistics): every live buffer and texture of the device, Encore's and
// Dawn's internal ones (staging, lazy-clear) alike, with the bytes Dawn estimates for them.
// Samplers, bind groups, pipelines and render bundles hold no device memory and are not in the
// dump; on lavapipe each descriptor set and buffer is a memory mapping, which
// processMemoryMappings() counts.

#include <cstdint>

#include <webgpu/webgpu_cpp.h>

namespace encore::gpu {

struct ResourceStatistics {
    std::uint64_t buffers = 0;
    std::uint64_t textures = 0;
    std::uint64_t bufferBytes = 0;
    std::uint64_t textureBytes = 0;
};

ResourceStatistics resourceStatistics(const wgpu::Device& device);

// Lines of /proc/self/maps (0 where it cannot be read).
std::uint64_t processMemoryMappings();

}  // namespace encore::gpu
