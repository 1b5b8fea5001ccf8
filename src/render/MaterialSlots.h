#pragma once

// The texture slots of a material, as one table (textureSlots()). Each row says, for one slot of
// material.wgsl: the name of its texture variable, the colour space its texture
// is sampled in, which SampledTextures switch uploads it, whether it is a normal map, and which
// scene::Material field it reads. The slot's texture, its colour space, whether it is uploaded
// and its uniform transform all come from this table rather than from switches over
// TextureSlot, so a new slot is one enumerator, one row and one declaration in material.wgsl;
// tests/unit/render/MaterialWgslTest.cpp checks the table against material.wgsl. Every place
// a new material extension touches: docs/adding-a-material-extension.md.
//
// CPU-only: no WebGPU, so the fuzzers and unit tests use it without a device.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "encore/scene/SceneData.h"

namespace encore::render {

// The texture slots of material.wgsl, in binding order.
enum class TextureSlot : std::uint32_t {
    BaseColor,          // Specular-glossiness: the diffuse texture.
    MetallicRoughness,  // Specular-glossiness: the specular-glossiness texture.
    Normal,
    Occlusion,
    Emissive,
    Specular,
    SpecularColor,
    Clearcoat,
    ClearcoatRoughness,
    ClearcoatNormal,
    SheenColor,
    SheenRoughness,
    Iridescence,
    IridescenceThickness,
    Anisotropy,
    Transmission,              // KHR_materials_transmission: red channel.
    Thickness,                 // KHR_materials_volume: green channel.
    DiffuseTransmission,       // KHR_materials_diffuse_transmission: alpha channel.
    DiffuseTransmissionColor,  // KHR_materials_diffuse_transmission: RGB, sRGB.
};
inline constexpr std::uint32_t kMaterialTextureSlotCount = 19;
// Slots before Iridescence: what a variant without MATERIAL_EXTENSIONS samples (and binds,
// BindGroupLayouts::materialBase).
inline constexpr std::uint32_t kMaterialBaseTextureSlotCount = 12;
static_assert(std::uint32_t(TextureSlot::Iridescence) == kMaterialBaseTextureSlotCount);
// The samplers a material binds (its sampler palette, SamplerPalette.h): the slots' textures
// share them, each slot naming its entry in the uniform, so a new slot needs no sampler binding
// (a shader stage may bind only 16 samplers; Dawn allows no more).
inline constexpr std::uint32_t kMaterialSamplerCount = 4;
// Group 2's bindings: 0 is the uniform, then the palette's samplers (material.wgsl's
// materialSampler0..3), then a texture per slot.
constexpr std::uint32_t materialSamplerBinding(std::uint32_t entry) {
    return 1 + entry;
}
constexpr std::uint32_t materialTextureBinding(std::uint32_t slot) {
    return 1 + kMaterialSamplerCount + slot;
}

enum class ColorSpace : std::uint8_t {
    Srgb,    // Colour data: base colour, emissive, specular and sheen colour.
    Linear,  // Non-colour data: metallic-roughness, normal, occlusion, factors.
};

// Which material texture slots are uploaded (with mip chains); references in the others are
// still validated. Encore's shading samples all of them. A slot's switch is its table row's
// `sampled` member.
struct SampledTextures {
    bool baseColor = true;
    bool metallicRoughness = true;
    bool normal = true;
    bool occlusion = true;
    bool emissive = true;
    bool extensions = true;  // Every extension's slots.

    static SampledTextures all() { return {}; }
    static SampledTextures baseColorOnly() { return {true, false, false, false, false, false}; }
    bool sampled(TextureSlot slot) const;
};

// One row of the slot table.
struct TextureSlotInfo {
    TextureSlot slot;
    // material.wgsl's texture variable, at @group(2) @binding(materialTextureBinding(slot)).
    std::string_view textureName;
    // The colour space of the slot's texture, and the one it has when the material uses
    // KHR_materials_pbrSpecularGlossiness (whose specular-glossiness texture, read through the
    // metallic-roughness slot, holds an sRGB specular colour; its alpha stays linear).
    ColorSpace colorSpace;
    ColorSpace specularGlossinessColorSpace;
    // The SampledTextures switch that uploads the slot's texture.
    bool SampledTextures::*sampled;
    // A tangent-space normal map or direction: a primitive drawn with it is worth binding
    // TANGENT for.
    bool normalMap;
    // The texture reference the slot reads: an empty optional when the material, or the
    // extension owning the slot, has none. The reference lives in `material`.
    const std::optional<scene::TextureRef>& (*texture)(const scene::Material& material);
};

// The table, indexed by TextureSlot.
std::span<const TextureSlotInfo, kMaterialTextureSlotCount> textureSlots();
const TextureSlotInfo& textureSlotInfo(TextureSlot slot);

// The texture reference of `material` in `slot` (nullopt when it has none).
std::optional<scene::TextureRef> slotTexture(const scene::Material& material, TextureSlot slot);

// The colour space a slot's texture is sampled in for `material`.
ColorSpace slotColorSpace(const scene::Material& material, TextureSlot slot);

// Whether the material uses an extension that only the MATERIAL_EXTENSIONS variant shades
// (iridescence, anisotropy, transmission with volume and dispersion, diffuse transmission):
// its pipelines and its bind group's layout follow, and an edit may not change it.
bool materialShadesExtensions(const scene::Material& material);
// Whether the material reads TEXCOORD_1 in any slot (a shader variant).
bool materialUsesTexcoord1(const scene::Material& material);
// Whether the material's shading reads the tangent frame (a normal map, base or clear coat, or
// KHR_materials_anisotropy): TANGENT is then worth binding.
bool materialUsesTangents(const scene::Material& material);

}  // namespace encore::render
