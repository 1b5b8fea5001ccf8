#pragma once

#include <webgpu/webgpu_cpp.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace encore::gpu {

// The size of a buffer for `size` bytes: a multiple of 4 (WebGPU requires it for mapped creation
// and for vertex/index data), at least 4.
inline std::uint64_t bufferSizeFor(std::uint64_t size) {
    return std::max<std::uint64_t>(4, (size + 3) & ~std::uint64_t{3});
}

// Creates a buffer of bufferSizeFor(size) bytes mapped (zeroed by WebGPU), has `fill` write into
// it (std::uint8_t* to the mapping) and unmaps it: data goes straight into the buffer, without a
// copy gathered first. `fill` is not called when the buffer could not be created (out of memory,
// which the device reports).
template <typename Fill>
wgpu::Buffer createBufferFilledBy(const wgpu::Device& device,
                                  wgpu::BufferUsage usage,
                                  std::uint64_t size,
                                  const std::string& label,
                                  Fill&& fill) {
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.size = bufferSizeFor(size);
    descriptor.usage = usage;
    descriptor.mappedAtCreation = true;
    wgpu::Buffer buffer = device.CreateBuffer(&descriptor);
    if (void* mapped = buffer.GetMappedRange(0, descriptor.size)) {
        fill(static_cast<std::uint8_t*>(mapped));
    }
    buffer.Unmap();
    return buffer;
}

// Creates a buffer holding `bytes`, its size rounded up to a multiple of 4 (WebGPU requires it
// for mapped creation and for vertex/index data) and zero-padded.
wgpu::Buffer createBufferWithData(const wgpu::Device& device,
                                  wgpu::BufferUsage usage,
                                  std::span<const std::uint8_t> bytes,
                                  const std::string& label);

template <typename T>
wgpu::Buffer createBufferFrom(const wgpu::Device& device,
                              wgpu::BufferUsage usage,
                              std::span<const T> values,
                              const std::string& label) {
    return createBufferWithData(
        device, usage,
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(values.data()),
                                      values.size_bytes()),
        label);
}

// A storage buffer (and `extra` usages) holding `values`; one zeroed element when there are
// none, as WebGPU binds no empty buffer.
template <typename T>
wgpu::Buffer createStorageBuffer(const wgpu::Device& device,
                                 std::span<const T> values,
                                 const std::string& label,
                                 wgpu::BufferUsage extra = wgpu::BufferUsage::None) {
    const T zero{};
    return createBufferFrom<T>(device, wgpu::BufferUsage::Storage | extra,
                               values.empty() ? std::span<const T>(&zero, 1) : values, label);
}

template <typename T>
wgpu::Buffer createStorageBuffer(const wgpu::Device& device,
                                 const std::vector<T>& values,
                                 const std::string& label,
                                 wgpu::BufferUsage extra = wgpu::BufferUsage::None) {
    return createStorageBuffer(device, std::span<const T>(values), label, extra);
}

// An uninitialised (zeroed by WebGPU) buffer of at least `size` bytes, rounded up to 4.
wgpu::Buffer createBuffer(const wgpu::Device& device,
                          wgpu::BufferUsage usage,
                          std::uint64_t size,
                          const std::string& label);

}  // namespace encore::gpu
