#include "gpu/BindingResource.h"

#include <array>
#include <vector>

namespace encore::gpu {

BindingResource::BindingResource(std::uint32_t binding,
                                 const wgpu::Buffer& buffer,
                                 std::uint64_t offset,
                                 std::uint64_t size) {
    resource.binding = binding;
    resource.buffer = buffer;
    resource.offset = offset;
    resource.size = size;
}

BindingResource::BindingResource(std::uint32_t binding, const wgpu::TextureView& view) {
    resource.binding = binding;
    resource.textureView = view;
}

BindingResource::BindingResource(std::uint32_t binding, const wgpu::Sampler& sampler) {
    resource.binding = binding;
    resource.sampler = sampler;
}

wgpu::BindGroup makeBindGroup(const wgpu::Device& device,
                              const wgpu::BindGroupLayout& layout,
                              std::span<const BindingResource> resources,
                              wgpu::StringView label) {
    // Some callers make a bind group per object (the animometer: up to a million), so the
    // usual handful of entries is copied to the stack rather than to the heap.
    constexpr std::size_t kOnStack = 16;
    std::array<wgpu::BindGroupEntry, kOnStack> onStack;
    std::vector<wgpu::BindGroupEntry> onHeap;
    wgpu::BindGroupEntry* entries = onStack.data();
    if (resources.size() > kOnStack) {
        onHeap.resize(resources.size());
        entries = onHeap.data();
    }
    for (std::size_t i = 0; i < resources.size(); ++i) {
        entries[i] = resources[i].resource;
    }
    wgpu::BindGroupDescriptor descriptor{};
    descriptor.label = label;
    descriptor.layout = layout;
    descriptor.entryCount = resources.size();
    descriptor.entries = entries;
    return device.CreateBindGroup(&descriptor);
}

wgpu::BindGroup makeBindGroup(const wgpu::Device& device,
                              const wgpu::BindGroupLayout& layout,
                              std::initializer_list<BindingResource> resources,
                              wgpu::StringView label) {
    return makeBindGroup(device, layout, std::span(resources.begin(), resources.size()), label);
}

}  // namespace encore::gpu
