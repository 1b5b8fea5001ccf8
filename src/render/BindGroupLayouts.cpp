#include "encore/render/BindGroupLayouts.h"

#include "encore/render/FrameUniforms.h"

namespace encore::render {

namespace {

wgpu::BindGroupLayout createLayout(const wgpu::Device& device, const char* label,
                                   std::initializer_list<wgpu::BindGroupLayoutEntry> entries) {
    wgpu::BindGroupLayoutDescriptor descriptor{};
    descriptor.label = label;
    descriptor.entryCount = entries.size();
    descriptor.entries = entries.begin();
    return device.CreateBindGroupLayout(&descriptor);
}

wgpu::BindGroupLayoutEntry bufferEntry(std::uint32_t binding, wgpu::ShaderStage visibility,
                                       wgpu::BufferBindingType type, std::uint64_t minSize) {
    wgpu::BindGroupLayoutEntry entry{};
    entry.binding = binding;
    entry.visibility = visibility;
    entry.buffer.type = type;
    entry.buffer.minBindingSize = minSize;
    return entry;
}

}  // namespace

BindGroupLayouts BindGroupLayouts::create(const wgpu::Device& device) {
    constexpr auto kVertexFragment = wgpu::ShaderStage::Vertex | wgpu::ShaderStage::Fragment;
    BindGroupLayouts layouts;
    layouts.frame = createLayout(device, "frame",
                                 {bufferEntry(0, kVertexFragment, wgpu::BufferBindingType::Uniform,
                                              sizeof(FrameUniform))});
    layouts.nodeUniform =
        createLayout(device, "node transform",
                     {bufferEntry(0, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::Uniform,
                                  sizeof(TransformUniform))});
    layouts.instanceStorage = createLayout(
        device, "instance transforms",
        {bufferEntry(0, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage,
                     sizeof(TransformUniform))});

    wgpu::BindGroupLayoutEntry visibleList =
        bufferEntry(1, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage, 4);
    visibleList.buffer.hasDynamicOffset = true;
    layouts.culledInstances = createLayout(
        device, "culled instances",
        {bufferEntry(0, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage,
                     sizeof(TransformUniform)),
         visibleList});

    wgpu::BindGroupLayoutEntry sampler{};
    sampler.binding = 1;
    sampler.visibility = wgpu::ShaderStage::Fragment;
    sampler.sampler.type = wgpu::SamplerBindingType::Filtering;
    wgpu::BindGroupLayoutEntry texture{};
    texture.binding = 2;
    texture.visibility = wgpu::ShaderStage::Fragment;
    texture.texture.sampleType = wgpu::TextureSampleType::Float;
    texture.texture.viewDimension = wgpu::TextureViewDimension::e2D;
    layouts.material = createLayout(
        device, "material",
        {bufferEntry(0, wgpu::ShaderStage::Fragment, wgpu::BufferBindingType::Uniform, 64), sampler,
         texture});
    return layouts;
}

}  // namespace encore::render
