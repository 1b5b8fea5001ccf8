#pragma once

// Bind group entries for buffers: the descriptor boilerplate every compute pass repeats.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

namespace encore::gpu {

// `size` bytes of `buffer` from `offset` (by default the whole buffer) at `binding`.
inline wgpu::BindGroupEntry bufferEntry(std::uint32_t binding, const wgpu::Buffer& buffer,
                                        std::uint64_t offset = 0,
                                        std::uint64_t size = wgpu::kWholeSize) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.buffer = buffer;
    entry.offset = offset;
    entry.size = size;
    return entry;
}

}  // namespace encore::gpu
