#pragma once

// Bind group entries for buffers, texture views and samplers: the descriptor boilerplate every
// pass repeats.

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

inline wgpu::BindGroupEntry textureEntry(std::uint32_t binding, const wgpu::TextureView& view) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.textureView = view;
    return entry;
}

inline wgpu::BindGroupEntry samplerEntry(std::uint32_t binding, const wgpu::Sampler& sampler) {
    wgpu::BindGroupEntry entry{};
    entry.binding = binding;
    entry.sampler = sampler;
    return entry;
}

}  // namespace encore::gpu
