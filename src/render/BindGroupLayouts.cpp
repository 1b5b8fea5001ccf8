#include "encore/render/BindGroupLayouts.h"

#include "encore/render/FrameUniforms.h"

#include <vector>

#include "encore/render/Lighting.h"
#include "encore/render/MaterialResources.h"

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

wgpu::BindGroupLayoutEntry textureEntry(std::uint32_t binding, wgpu::TextureViewDimension dimension) {
    wgpu::BindGroupLayoutEntry entry{};
    entry.binding = binding;
    entry.visibility = wgpu::ShaderStage::Fragment;
    entry.texture.sampleType = wgpu::TextureSampleType::Float;
    entry.texture.viewDimension = dimension;
    return entry;
}

wgpu::BindGroupLayoutEntry samplerEntry(std::uint32_t binding) {
    wgpu::BindGroupLayoutEntry entry{};
    entry.binding = binding;
    entry.visibility = wgpu::ShaderStage::Fragment;
    entry.sampler.type = wgpu::SamplerBindingType::Filtering;
    return entry;
}

}  // namespace

BindGroupLayouts BindGroupLayouts::create(const wgpu::Device& device) {
    constexpr auto kVertexFragment = wgpu::ShaderStage::Vertex | wgpu::ShaderStage::Fragment;
    BindGroupLayouts layouts;
    // Group 0: the camera, then how the scene is lit (scene_lighting.wgsl). Every pipeline uses
    // this layout, so strategies without materials simply ignore bindings 1..4.
    layouts.frame = createLayout(
        device, "frame",
        {bufferEntry(0, kVertexFragment, wgpu::BufferBindingType::Uniform, sizeof(FrameUniform)),
         bufferEntry(1, wgpu::ShaderStage::Fragment, wgpu::BufferBindingType::Uniform,
                     sizeof(LightingUniform)),
         bufferEntry(2, wgpu::ShaderStage::Fragment, wgpu::BufferBindingType::ReadOnlyStorage,
                     sizeof(LightUniform)),
         textureEntry(3, wgpu::TextureViewDimension::e2D), samplerEntry(4)});
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

    // Group 2: the material uniform, then a sampler and a texture per slot (material.wgsl).
    std::vector<wgpu::BindGroupLayoutEntry> material = {bufferEntry(
        0, wgpu::ShaderStage::Fragment, wgpu::BufferBindingType::Uniform, sizeof(MaterialUniform))};
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        material.push_back(samplerEntry(materialSamplerBinding(slot)));
        material.push_back(textureEntry(materialTextureBinding(slot), wgpu::TextureViewDimension::e2D));
    }
    wgpu::BindGroupLayoutDescriptor materialDescriptor{};
    materialDescriptor.label = "material";
    materialDescriptor.entryCount = material.size();
    materialDescriptor.entries = material.data();
    layouts.material = device.CreateBindGroupLayout(&materialDescriptor);
    layouts.materialUniformOnly = createLayout(
        device, "material (uniform only)",
        {bufferEntry(0, wgpu::ShaderStage::Fragment, wgpu::BufferBindingType::Uniform,
                     sizeof(MaterialUniform))});
    // Group 3 (2 without materials): skinning and morphing (AnimationBuffers).
    wgpu::BindGroupLayoutEntry animationDraw =
        bufferEntry(0, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::Uniform, 20);
    animationDraw.buffer.hasDynamicOffset = true;
    layouts.animation = createLayout(
        device, "animation",
        {animationDraw,
         bufferEntry(1, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage,
                     sizeof(TransformUniform)),
         bufferEntry(2, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage, 4),
         bufferEntry(3, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage, 16),
         bufferEntry(4, wgpu::ShaderStage::Vertex, wgpu::BufferBindingType::ReadOnlyStorage, 8)});
    return layouts;
}

}  // namespace encore::render
