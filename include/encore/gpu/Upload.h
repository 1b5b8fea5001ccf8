#pragma once

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

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

// A storage buffer (and `extra` usages) holding `values`; one zeroed element when there are
// none, as WebGPU binds no empty buffer.
template <typename T>
wgpu::Buffer createStorageBuffer(const wgpu::Device& device, std::span<const T> values,
                                 const std::string& label,
                                 wgpu::BufferUsage extra = wgpu::BufferUsage::None) {
    const T zero{};
    return createBufferFrom<T>(device, wgpu::BufferUsage::Storage | extra,
                               values.empty() ? std::span<const T>(&zero, 1) : values, label);
}

template <typename T>
wgpu::Buffer createStorageBuffer(const wgpu::Device& device, const std::vector<T>& values,
                                 const std::string& label,
                                 wgpu::BufferUsage extra = wgpu::BufferUsage::None) {
    return createStorageBuffer(device, std::span<const T>(values), label, extra);
}

// An uninitialised (zeroed by WebGPU) buffer of at least `size` bytes, rounded up to 4.
wgpu::Buffer createBuffer(const wgpu::Device& device, wgpu::BufferUsage usage, std::uint64_t size,
                          const std::string& label);

}  // namespace encore::gpu
