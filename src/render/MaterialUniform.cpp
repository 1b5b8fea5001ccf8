#include "render/MaterialUniform.h"

#include <cmath>

namespace encore::render {

namespace {

void setVector(float (&out)[4], float x, float y, float z, float w) {
    out[0] = x;
    out[1] = y;
    out[2] = z;
    out[3] = w;
}

// KHR_texture_transform: Translation * Rotation * Scale, with Rotation = [cos sin; -sin cos]
// (the extension's convention, not the usual one), as the two rows of a 2x3 matrix.
TextureSlotUniform makeSlotUniform(const std::optional<scene::TextureRef>& texture,
                                   std::uint32_t samplerEntry) {
    scene::TextureTransform transform;
    if (texture && texture->transform) {
        transform = *texture->transform;
    }
    const float c = std::cos(transform.rotation);
    const float s = std::sin(transform.rotation);
    TextureSlotUniform slot{};
    setVector(slot.row0, c * transform.scale.x, s * transform.scale.y, transform.offset.x,
              texture && texture->texCoord == 1 ? 1.0f : 0.0f);
    setVector(slot.row1, -s * transform.scale.x, c * transform.scale.y, transform.offset.y,
              float(samplerEntry));
    return slot;
}

}  // namespace

MaterialUniform makeMaterialUniform(const scene::Material& material,
                                    const SlotSamplerEntries& samplerEntries) {
    MaterialUniform uniform{};
    const glm::vec4& base = material.baseColorFactor;
    setVector(uniform.baseColorFactor, base.r, base.g, base.b, base.a);
    const glm::vec3 emissive = material.emissiveFactor * material.emissiveStrength;
    setVector(uniform.emissive, emissive.r, emissive.g, emissive.b, 0.0f);
    setVector(uniform.metallicRoughness, material.metallicFactor, material.roughnessFactor,
              material.normalScale, material.occlusionStrength);
    setVector(uniform.alpha,
              material.alphaMode == scene::AlphaMode::Mask ? material.alphaCutoff : 0.0f,
              material.alphaMode == scene::AlphaMode::Blend ? 1.0f : 0.0f, material.ior, 0.0f);
    std::uint32_t features = 0;
    if (material.normalTexture) {
        features |= kMaterialNormalMap;
    }
    setVector(uniform.specular, 1.0f, 1.0f, 1.0f, 1.0f);
    if (material.specular) {
        const scene::SpecularExtension& specular = *material.specular;
        setVector(uniform.specular, specular.specularColorFactor.r, specular.specularColorFactor.g,
                  specular.specularColorFactor.b, specular.specularFactor);
        features |= kMaterialSpecular;
    }
    if (material.clearcoat) {
        const scene::ClearcoatExtension& clearcoat = *material.clearcoat;
        setVector(uniform.clearcoat, clearcoat.clearcoatFactor, clearcoat.clearcoatRoughnessFactor,
                  clearcoat.clearcoatNormalScale, 0.0f);
        features |= kMaterialClearcoat;
        if (clearcoat.clearcoatNormalTexture) {
            features |= kMaterialClearcoatNormalMap;
        }
    }
    if (material.sheen) {
        const scene::SheenExtension& sheen = *material.sheen;
        setVector(uniform.sheen, sheen.sheenColorFactor.r, sheen.sheenColorFactor.g,
                  sheen.sheenColorFactor.b, sheen.sheenRoughnessFactor);
        features |= kMaterialSheen;
    }
    if (material.iridescence) {
        const scene::IridescenceExtension& iridescence = *material.iridescence;
        setVector(uniform.iridescence, iridescence.iridescenceFactor, iridescence.iridescenceIor,
                  iridescence.iridescenceThicknessMinimum, iridescence.iridescenceThicknessMaximum);
        features |= kMaterialIridescence;
    }
    if (material.anisotropy) {
        const scene::AnisotropyExtension& anisotropy = *material.anisotropy;
        setVector(uniform.anisotropy, std::cos(anisotropy.anisotropyRotation),
                  std::sin(anisotropy.anisotropyRotation), anisotropy.anisotropyStrength, 0.0f);
        features |= kMaterialAnisotropy;
        if (anisotropy.anisotropyTexture) {
            features |= kMaterialAnisotropyTexture;
        }
    }
    setVector(uniform.attenuationColor, 1.0f, 1.0f, 1.0f, 0.0f);
    // KHR_materials_volume acts only through transmission or diffuse transmission (the
    // extension says so), dispersion only through a transmissive volume.
    float thickness = 0.0f;
    float distance = 0.0f;
    if (material.volume && (material.transmission || material.diffuseTransmission)) {
        const scene::VolumeExtension& volume = *material.volume;
        thickness = volume.thicknessFactor;
        distance = std::isfinite(volume.attenuationDistance) ? volume.attenuationDistance : 0.0f;
        setVector(uniform.attenuationColor, volume.attenuationColor.r, volume.attenuationColor.g,
                  volume.attenuationColor.b, 0.0f);
        features |= kMaterialVolume;
    }
    if (material.transmission) {
        const float dispersion =
            material.volume && material.dispersion ? material.dispersion->dispersion : 0.0f;
        setVector(uniform.transmission, material.transmission->transmissionFactor, thickness,
                  distance, dispersion);
        features |= kMaterialTransmission;
    } else {
        setVector(uniform.transmission, 0.0f, thickness, distance, 0.0f);
    }
    if (material.diffuseTransmission) {
        const scene::DiffuseTransmissionExtension& diffuse = *material.diffuseTransmission;
        setVector(uniform.diffuseTransmission, diffuse.diffuseTransmissionColorFactor.r,
                  diffuse.diffuseTransmissionColorFactor.g,
                  diffuse.diffuseTransmissionColorFactor.b, diffuse.diffuseTransmissionFactor);
        features |= kMaterialDiffuseTransmission;
    }
    ShadingModel model = ShadingModel::MetallicRoughness;
    if (material.specularGlossiness) {
        const scene::SpecularGlossinessExtension& glossiness = *material.specularGlossiness;
        setVector(uniform.specularGlossiness, glossiness.specularFactor.r,
                  glossiness.specularFactor.g, glossiness.specularFactor.b,
                  glossiness.glossinessFactor);
        model = ShadingModel::SpecularGlossiness;
    }
    if (material.unlit) {
        model = ShadingModel::Unlit;
    }
    uniform.flags[0] = std::uint32_t(model);
    uniform.flags[1] = features;
    for (const TextureSlotInfo& slot : textureSlots()) {
        const std::uint32_t index = std::uint32_t(slot.slot);
        uniform.slots[index] = makeSlotUniform(slot.texture(material), samplerEntries[index]);
    }
    return uniform;
}

}  // namespace encore::render
