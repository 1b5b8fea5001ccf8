#pragma once

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <string>

namespace encore::gpu {

// Creates a buffer holding `bytes`, its size rounded up to a multiple of 4 (WebGPU requires it
// for mapped creation and for vertex/index data) and zero-padded.
wgpu::Buffer createBufferWithData(const wgpu::Device& device, wgpu::BufferUsage usage,
                                  std::span<const std::uint8_t> bytes, const std::string& label);

template <typename T>
wgpu::Buffer createBufferFrom(const wgpu::Device& device, wgpu::BufferUsage usage,
                              std::span<const T> values, const std::string& label) {
    return createBufferWithData(
        device, usage,
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(values.data()),
                                      values.size_bytes()),
        label);
}

// An uninitialised (zeroed by WebGPU) buffer of at least `size` bytes, rounded up to 4.
wgpu::Buffer createBuffer(const wgpu::Device& device, wgpu::BufferUsage usage, std::uint64_t size,
                          const std::string& label);

}  // namespace encore::gpu
