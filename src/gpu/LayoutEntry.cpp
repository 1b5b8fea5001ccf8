#include "gpu/LayoutEntry.h"

#include <vector>

namespace encore::gpu {

namespace {

// The fields every kind of entry sets.
LayoutEntry entryAt(std::uint32_t binding, wgpu::ShaderStage visibility) {
    LayoutEntry layout;
    layout.entry.binding = binding;
    layout.entry.visibility = visibility;
    return layout;
}

LayoutEntry bufferLayout(std::uint32_t binding,
                         wgpu::ShaderStage visibility,
                         wgpu::BufferBindingType type,
                         std::uint64_t minBindingSize) {
    LayoutEntry layout = entryAt(binding, visibility);
    layout.entry.buffer.type = type;
    layout.entry.buffer.minBindingSize = minBindingSize;
    return layout;
}

}  // namespace

LayoutEntry LayoutEntry::uniform(std::uint32_t binding,
                                 wgpu::ShaderStage visibility,
                                 std::uint64_t minBindingSize) {
    return bufferLayout(binding, visibility, wgpu::BufferBindingType::Uniform, minBindingSize);
}

LayoutEntry LayoutEntry::storage(std::uint32_t binding,
                                 wgpu::ShaderStage visibility,
                                 std::uint64_t minBindingSize) {
    return bufferLayout(binding, visibility, wgpu::BufferBindingType::Storage, minBindingSize);
}

LayoutEntry LayoutEntry::readOnlyStorage(std::uint32_t binding,
                                         wgpu::ShaderStage visibility,
                                         std::uint64_t minBindingSize) {
    return bufferLayout(binding, visibility, wgpu::BufferBindingType::ReadOnlyStorage,
                        minBindingSize);
}

LayoutEntry LayoutEntry::texture(std::uint32_t binding,
                                 wgpu::ShaderStage visibility,
                                 wgpu::TextureSampleType sampleType,
                                 wgpu::TextureViewDimension viewDimension,
                                 bool multisampled) {
    LayoutEntry layout = entryAt(binding, visibility);
    layout.entry.texture.sampleType = sampleType;
    layout.entry.texture.viewDimension = viewDimension;
    layout.entry.texture.multisampled = multisampled;
    return layout;
}

LayoutEntry LayoutEntry::sampler(std::uint32_t binding,
                                 wgpu::ShaderStage visibility,
                                 wgpu::SamplerBindingType type) {
    LayoutEntry layout = entryAt(binding, visibility);
    layout.entry.sampler.type = type;
    return layout;
}

LayoutEntry LayoutEntry::storageTexture(std::uint32_t binding,
                                        wgpu::ShaderStage visibility,
                                        wgpu::TextureFormat format,
                                        wgpu::StorageTextureAccess access,
                                        wgpu::TextureViewDimension viewDimension) {
    LayoutEntry layout = entryAt(binding, visibility);
    layout.entry.storageTexture.access = access;
    layout.entry.storageTexture.format = format;
    layout.entry.storageTexture.viewDimension = viewDimension;
    return layout;
}

LayoutEntry LayoutEntry::withDynamicOffset() const {
    LayoutEntry layout = *this;
    layout.entry.buffer.hasDynamicOffset = true;
    return layout;
}

wgpu::BindGroupLayout makeBindGroupLayout(const wgpu::Device& device,
                                          std::span<const LayoutEntry> entries,
                                          wgpu::StringView label) {
    // Layouts are made once per pass or scene, not per frame: a vector costs nothing here.
    std::vector<wgpu::BindGroupLayoutEntry> layoutEntries;
    layoutEntries.reserve(entries.size());
    for (const LayoutEntry& layout : entries) {
        layoutEntries.push_back(layout.entry);
    }
    wgpu::BindGroupLayoutDescriptor descriptor{};
    descriptor.label = label;
    descriptor.entryCount = layoutEntries.size();
    descriptor.entries = layoutEntries.data();
    return device.CreateBindGroupLayout(&descriptor);
}

wgpu::BindGroupLayout makeBindGroupLayout(const wgpu::Device& device,
                                          std::initializer_list<LayoutEntry> entries,
                                          wgpu::StringView label) {
    return makeBindGroupLayout(device, std::span(entries.begin(), entries.size()), label);
}

wgpu::PipelineLayout makePipelineLayout(const wgpu::Device& device,
                                        std::span<const wgpu::BindGroupLayout> groups,
                                        wgpu::StringView label) {
    wgpu::PipelineLayoutDescriptor descriptor{};
    descriptor.label = label;
    descriptor.bindGroupLayoutCount = groups.size();
    descriptor.bindGroupLayouts = groups.data();
    return device.CreatePipelineLayout(&descriptor);
}

wgpu::PipelineLayout makePipelineLayout(const wgpu::Device& device,
                                        std::initializer_list<wgpu::BindGroupLayout> groups,
                                        wgpu::StringView label) {
    return makePipelineLayout(device, std::span(groups.begin(), groups.size()), label);
}

}  // namespace encore::gpu
