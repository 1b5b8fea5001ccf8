#include "encore/gpu/Upload.h"

#include <algorithm>
#include <cstring>

namespace encore::gpu {

namespace {
std::uint64_t roundUpTo4(std::uint64_t size) {
    return std::max<std::uint64_t>(4, (size + 3) & ~std::uint64_t{3});
}
}  // namespace

wgpu::Buffer createBufferWithData(const wgpu::Device& device, wgpu::BufferUsage usage,
                                  std::span<const std::uint8_t> bytes, const std::string& label) {
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.size = roundUpTo4(bytes.size());
    descriptor.usage = usage;
    descriptor.mappedAtCreation = true;
    wgpu::Buffer buffer = device.CreateBuffer(&descriptor);
    if (void* mapped = buffer.GetMappedRange(0, descriptor.size)) {
        auto* destination = static_cast<std::uint8_t*>(mapped);
        if (!bytes.empty()) {
            std::memcpy(destination, bytes.data(), bytes.size());
        }
        std::memset(destination + bytes.size(), 0, descriptor.size - bytes.size());
    }
    buffer.Unmap();
    return buffer;
}

wgpu::Buffer createBuffer(const wgpu::Device& device, wgpu::BufferUsage usage, std::uint64_t size,
                          const std::string& label) {
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.size = roundUpTo4(size);
    descriptor.usage = usage;
    return device.CreateBuffer(&descriptor);
}

}  // namespace encore::gpu
