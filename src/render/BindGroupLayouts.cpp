#include "render/BindGroupLayouts.h"

#include "render/FrameUniforms.h"

#include <vector>

#include "gpu/LayoutEntry.h"
#include "render/Lighting.h"
#include "render/MaterialResources.h"

namespace encore::render {

BindGroupLayouts BindGroupLayouts::create(const wgpu::Device& device) {
    using gpu::LayoutEntry;
    constexpr auto kVertex = wgpu::ShaderStage::Vertex;
    // Lighting and materials are also read by the visibility strategy's compute resolve.
    constexpr auto kFragment = wgpu::ShaderStage::Fragment | wgpu::ShaderStage::Compute;
    BindGroupLayouts layouts;
    // Group 0: the camera, then how the scene is lit (scene_lighting.wgsl) and what lies behind
    // transmissive surfaces (transmission.wgsl). Every pipeline uses this layout, so strategies
    // without materials simply ignore bindings 1..5.
    layouts.frame = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, kVertex | kFragment, sizeof(FrameUniform)),
         LayoutEntry::uniform(1, kFragment, sizeof(LightingUniform)),
         LayoutEntry::readOnlyStorage(2, kFragment, sizeof(LightUniform)),
         LayoutEntry::texture(3, kFragment), LayoutEntry::sampler(4, kFragment),
         LayoutEntry::texture(5, kFragment)},
        "frame");
    layouts.nodeUniform = gpu::makeBindGroupLayout(
        device, {LayoutEntry::uniform(0, kVertex, sizeof(TransformUniform))}, "node transform");
    layouts.instanceStorage = gpu::makeBindGroupLayout(
        device, {LayoutEntry::readOnlyStorage(0, kVertex, sizeof(TransformUniform))},
        "instance transforms");
    layouts.culledInstances = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::readOnlyStorage(0, kVertex, sizeof(TransformUniform)),
         LayoutEntry::readOnlyStorage(1, kVertex, 4).withDynamicOffset()},
        "culled instances");

    // Group 2: the material uniform, its sampler palette, then a texture per slot
    // (material.wgsl).
    std::vector<LayoutEntry> material = {
        LayoutEntry::uniform(0, kFragment, sizeof(MaterialUniform))};
    for (std::uint32_t entry = 0; entry < kMaterialSamplerCount; ++entry) {
        material.push_back(LayoutEntry::sampler(materialSamplerBinding(entry), kFragment));
    }
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        material.push_back(LayoutEntry::texture(materialTextureBinding(slot), kFragment));
    }
    layouts.material = gpu::makeBindGroupLayout(device, material, "material");
    material.resize(1 + kMaterialSamplerCount + kMaterialBaseTextureSlotCount);
    layouts.materialBase = gpu::makeBindGroupLayout(device, material, "material (base slots)");
    layouts.materialUniformOnly = gpu::makeBindGroupLayout(
        device, {LayoutEntry::uniform(0, kFragment, sizeof(MaterialUniform))},
        "material (uniform only)");
    // Group 3 (2 without materials): skinning and morphing (AnimationBuffers).
    layouts.animation = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, kVertex, 20).withDynamicOffset(),
         LayoutEntry::readOnlyStorage(1, kVertex, sizeof(TransformUniform)),
         LayoutEntry::readOnlyStorage(2, kVertex, 4), LayoutEntry::readOnlyStorage(3, kVertex, 16),
         LayoutEntry::readOnlyStorage(4, kVertex, 8)},
        "animation");
    return layouts;
}

}  // namespace encore::render
