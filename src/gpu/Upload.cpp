#include "gpu/Upload.h"

#include <algorithm>
#include <cstring>

#include "core/Bytes.h"

namespace encore::gpu {

wgpu::Buffer createBufferWithData(const wgpu::Device& device,
                                  wgpu::BufferUsage usage,
                                  std::span<const std::uint8_t> bytes,
                                  const std::string& label) {
    return createBufferFilledBy(device, usage, bytes.size(), label, [&](std::uint8_t* mapped) {
        copyBytes(mapped, bytes.data(), bytes.size());
        std::memset(mapped + bytes.size(), 0, bufferSizeFor(bytes.size()) - bytes.size());
    });
}

wgpu::Buffer createBuffer(const wgpu::Device& device,
                          wgpu::BufferUsage usage,
                          std::uint64_t size,
                          const std::string& label) {
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.size = bufferSizeFor(size);
    descriptor.usage = usage;
    return device.CreateBuffer(&descriptor);
}

}  // namespace encore::gpu
