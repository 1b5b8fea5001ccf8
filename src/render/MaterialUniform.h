#pragma once

// The uniform half of a material: MaterialUniform is the `Material` struct of material.wgsl
// byte for byte, and makeMaterialUniform packs a scene::Material into it (factors, shading
// model, feature bits, and each texture slot's texCoord set, KHR_texture_transform and sampler).
// CPU-only: MaterialResources uploads the result; tests and fuzzers call it without a device.
// tests/unit/render/MaterialWgslTest.cpp checks the layout and the constants against the WGSL.

#include <array>
#include <cstdint>

#include "encore/scene/SceneData.h"
#include "render/MaterialSlots.h"

namespace encore::render {

// One slot's texture coordinates: the rows of its 2x3 KHR_texture_transform matrix; row0[3] is
// 1 when the slot reads TEXCOORD_1; row1[3] is the entry of the material's sampler palette the
// slot samples with (SamplerPalette.h; 0 to 3, a whole number).
struct TextureSlotUniform {
    float row0[4];
    float row1[4];
};

// MaterialUniform::flags[0] (material.wgsl's kModel*).
enum class ShadingModel : std::uint32_t {
    MetallicRoughness = 0,
    SpecularGlossiness = 1,  // KHR_materials_pbrSpecularGlossiness.
    Unlit = 2,               // KHR_materials_unlit (wins over specular-glossiness).
};

// Bits of MaterialUniform::flags[1] (material.wgsl's kMaterial*).
inline constexpr std::uint32_t kMaterialNormalMap = 1;
inline constexpr std::uint32_t kMaterialClearcoatNormalMap = 2;
inline constexpr std::uint32_t kMaterialClearcoat = 4;
inline constexpr std::uint32_t kMaterialSheen = 8;
inline constexpr std::uint32_t kMaterialSpecular = 16;
inline constexpr std::uint32_t kMaterialIridescence = 32;
inline constexpr std::uint32_t kMaterialAnisotropy = 64;
inline constexpr std::uint32_t kMaterialAnisotropyTexture = 128;  // Its direction is textured.
// KHR_materials_transmission (and volume, dispersion).
inline constexpr std::uint32_t kMaterialTransmission = 1024;
inline constexpr std::uint32_t kMaterialVolume = 2048;
inline constexpr std::uint32_t kMaterialDiffuseTransmission = 4096;

// The `Material` struct of material.wgsl, byte for byte.
struct MaterialUniform {
    float baseColorFactor[4];
    float emissive[4];            // emissiveFactor * emissiveStrength.
    float metallicRoughness[4];   // metallic, roughness, normal scale, occlusion strength.
    float alpha[4];               // alphaCutoff (MASK only, 0 stays 0), BLEND flag, IOR.
    float specular[4];            // Specular colour factor, specular factor.
    float clearcoat[4];           // Factor, roughness factor, normal scale.
    float sheen[4];               // Colour factor, roughness factor.
    float specularGlossiness[4];  // Specular factor, glossiness factor.
    float iridescence[4];         // Factor, film IOR, thickness minimum, maximum (nm).
    float anisotropy[4];          // cos(rotation), sin(rotation), strength.
    // Transmission factor, thickness factor, attenuation distance (0: none), dispersion. The
    // volume's values are set with transmission or diffuse transmission (the volume's hosts).
    float transmission[4];
    float attenuationColor[4];     // KHR_materials_volume's attenuation colour.
    float diffuseTransmission[4];  // Colour factor, factor.
    // ShadingModel, kMaterial* bits, 1 + material index, bits of the slots bound to a texture
    // (MaterialResources sets the last two).
    std::uint32_t flags[4];
    TextureSlotUniform slots[kMaterialTextureSlotCount];  // Indexed by TextureSlot.
};
static_assert(sizeof(MaterialUniform) == 832);

// Each texture slot's entry in its material's sampler palette (SamplerPalette::slotEntries).
using SlotSamplerEntries = std::array<std::uint32_t, kMaterialTextureSlotCount>;

// The uniform contents of `material` whose slots sample with `samplerEntries` (no GPU
// involved).
MaterialUniform makeMaterialUniform(const scene::Material& material,
                                    const SlotSamplerEntries& samplerEntries = {});

}  // namespace encore::render
