#include "render/visibility/VisibilityWorkBuffers.h"

#include <algorithm>

#include "gpu/Upload.h"

namespace encore::render {

namespace {

void ensureBuffer(const wgpu::Device& device,
                  wgpu::Buffer& buffer,
                  std::uint64_t bytes,
                  wgpu::BufferUsage usage,
                  const char* label) {
    bytes = std::max<std::uint64_t>(bytes, 4);
    if (!buffer || buffer.GetSize() < bytes) {
        buffer = nullptr;  // Released before its successor is made: the two need not fit at once.
        buffer = gpu::createBuffer(device, usage, bytes, label);
    }
}

}  // namespace

void VisibilityWorkBuffers::ensure(const wgpu::Device& device, const Sizes& sizes) {
    ensureBuffer(device, units, sizes.units,
                 wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst, "visibility units");
    ensureBuffer(device, hardwareList, sizes.hardwareList, wgpu::BufferUsage::Storage,
                 "visibility hardware triangles");
    ensureBuffer(device, workgroupList, sizes.workgroupList, wgpu::BufferUsage::Storage,
                 "visibility workgroup blocks");
    ensureBuffer(device, bins, sizes.bins,
                 wgpu::BufferUsage::Storage | wgpu::BufferUsage::Uniform |
                     wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                 "visibility bins");
}

}  // namespace encore::render
