#include "RenderBridge.h"

#include "render/GltfToWebGpu.h"
#include "render/MaterialResources.h"
#include "render/VertexBindings.h"

namespace encore::fuzz {

bool bindsAttribute(scene::Semantic semantic) {
    return render::shaderLocation(semantic).has_value();
}

bool hasVertexFormat(const scene::Accessor& accessor) {
    return render::vertexFormat(accessor).has_value();
}

bool hasIndexFormat(const scene::Accessor& accessor) {
    const wgpu::IndexFormat format = render::indexFormat(accessor);
    return format == wgpu::IndexFormat::Uint16 || format == wgpu::IndexFormat::Uint32;
}

std::size_t paddedVertexBytes(const scene::SceneData& scene,
                              scene::AccessorId accessor,
                              std::uint32_t& stride) {
    return render::paddedVertexElements(scene, accessor, stride).size();
}

float materialUniformChecksum(const scene::Material& material) {
    const render::MaterialUniform uniform = render::makeMaterialUniform(material);
    float sum = float(render::materialUsesTexcoord1(material)) +
                float(render::materialUsesTangents(material));
    for (std::uint32_t slot = 0; slot < render::kMaterialTextureSlotCount; ++slot) {
        sum += float(render::slotColorSpace(material, render::TextureSlot(slot)));
    }
    for (const float value : uniform.alpha) {
        sum += value;
    }
    return sum + float(uniform.flags[0]);
}

std::uint32_t materialSlotCount() {
    return render::kMaterialTextureSlotCount;
}

std::optional<scene::TextureRef> materialSlotTexture(const scene::Material& material,
                                                     std::uint32_t slot) {
    return render::slotTexture(material, render::TextureSlot(slot));
}

std::uint32_t samplerChecksum(const scene::Sampler& sampler) {
    return std::uint32_t(render::filterMode(sampler.magFilter)) +
           std::uint32_t(render::filterMode(sampler.minFilter)) +
           std::uint32_t(render::mipmapFilterMode(sampler.mipmapFilter)) +
           std::uint32_t(render::addressMode(sampler.wrapS)) +
           std::uint32_t(render::addressMode(sampler.wrapT));
}

}  // namespace encore::fuzz
