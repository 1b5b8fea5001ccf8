#include "render/MaterialSlots.h"

#include <algorithm>
#include <array>
#include <cassert>

namespace encore::render {

namespace {

using TextureRefField = std::optional<scene::TextureRef>;

// What an absent extension's slots read.
constinit const TextureRefField kNoTexture;

// A texture of the core material.
template <TextureRefField scene::Material::*Field>
const TextureRefField& coreTexture(const scene::Material& material) {
    return material.*Field;
}

// A texture of an extension, empty while the material lacks the extension.
template <auto Extension, auto Field>
const TextureRefField& extensionTexture(const scene::Material& material) {
    const auto& extension = material.*Extension;
    return extension ? (*extension).*Field : kNoTexture;
}

// KHR_materials_pbrSpecularGlossiness replaces the metallic-roughness texture (the one the file
// may also carry is a fallback for viewers without the extension), even when it has none.
const TextureRefField& metallicRoughnessTexture(const scene::Material& material) {
    return material.specularGlossiness ? material.specularGlossiness->specularGlossinessTexture
                                       : material.metallicRoughnessTexture;
}

using Material = scene::Material;
using Sampled = SampledTextures;
constexpr ColorSpace kSrgb = ColorSpace::Srgb;
constexpr ColorSpace kLinear = ColorSpace::Linear;

// clang-format off
constexpr std::array<TextureSlotInfo, kMaterialTextureSlotCount> kSlots = {{
    {TextureSlot::BaseColor, "baseColorTexture", kSrgb, kSrgb, &Sampled::baseColor, false,
     &coreTexture<&Material::baseColorTexture>},
    // The specular-glossiness texture holds an sRGB specular colour (alpha stays linear).
    {TextureSlot::MetallicRoughness, "metallicRoughnessTexture", kLinear, kSrgb,
     &Sampled::metallicRoughness, false, &metallicRoughnessTexture},
    {TextureSlot::Normal, "normalTexture", kLinear, kLinear, &Sampled::normal, true,
     &coreTexture<&Material::normalTexture>},
    {TextureSlot::Occlusion, "occlusionTexture", kLinear, kLinear, &Sampled::occlusion, false,
     &coreTexture<&Material::occlusionTexture>},
    {TextureSlot::Emissive, "emissiveTexture", kSrgb, kSrgb, &Sampled::emissive, false,
     &coreTexture<&Material::emissiveTexture>},
    {TextureSlot::Specular, "specularTexture", kLinear, kLinear, &Sampled::extensions, false,
     &extensionTexture<&Material::specular, &scene::SpecularExtension::specularTexture>},
    {TextureSlot::SpecularColor, "specularColorTexture", kSrgb, kSrgb, &Sampled::extensions, false,
     &extensionTexture<&Material::specular, &scene::SpecularExtension::specularColorTexture>},
    {TextureSlot::Clearcoat, "clearcoatTexture", kLinear, kLinear, &Sampled::extensions, false,
     &extensionTexture<&Material::clearcoat, &scene::ClearcoatExtension::clearcoatTexture>},
    {TextureSlot::ClearcoatRoughness, "clearcoatRoughnessTexture", kLinear, kLinear,
     &Sampled::extensions, false,
     &extensionTexture<&Material::clearcoat,
                       &scene::ClearcoatExtension::clearcoatRoughnessTexture>},
    {TextureSlot::ClearcoatNormal, "clearcoatNormalTexture", kLinear, kLinear,
     &Sampled::extensions, true,
     &extensionTexture<&Material::clearcoat, &scene::ClearcoatExtension::clearcoatNormalTexture>},
    {TextureSlot::SheenColor, "sheenColorTexture", kSrgb, kSrgb, &Sampled::extensions, false,
     &extensionTexture<&Material::sheen, &scene::SheenExtension::sheenColorTexture>},
    {TextureSlot::SheenRoughness, "sheenRoughnessTexture", kLinear, kLinear,
     &Sampled::extensions, false,
     &extensionTexture<&Material::sheen, &scene::SheenExtension::sheenRoughnessTexture>},
    {TextureSlot::Iridescence, "iridescenceTexture", kLinear, kLinear, &Sampled::extensions,
     false,
     &extensionTexture<&Material::iridescence, &scene::IridescenceExtension::iridescenceTexture>},
    {TextureSlot::IridescenceThickness, "iridescenceThicknessTexture", kLinear, kLinear,
     &Sampled::extensions, false,
     &extensionTexture<&Material::iridescence,
                       &scene::IridescenceExtension::iridescenceThicknessTexture>},
    // The direction is read in tangent space, as a normal map's.
    {TextureSlot::Anisotropy, "anisotropyTexture", kLinear, kLinear, &Sampled::extensions, true,
     &extensionTexture<&Material::anisotropy, &scene::AnisotropyExtension::anisotropyTexture>},
    {TextureSlot::Transmission, "transmissionTexture", kLinear, kLinear, &Sampled::extensions,
     false,
     &extensionTexture<&Material::transmission,
                       &scene::TransmissionExtension::transmissionTexture>},
    {TextureSlot::Thickness, "thicknessTexture", kLinear, kLinear, &Sampled::extensions, false,
     &extensionTexture<&Material::volume, &scene::VolumeExtension::thicknessTexture>},
    {TextureSlot::DiffuseTransmission, "diffuseTransmissionTexture", kLinear, kLinear,
     &Sampled::extensions, false,
     &extensionTexture<&Material::diffuseTransmission,
                       &scene::DiffuseTransmissionExtension::diffuseTransmissionTexture>},
    {TextureSlot::DiffuseTransmissionColor, "diffuseTransmissionColorTexture", kSrgb, kSrgb,
     &Sampled::extensions, false,
     &extensionTexture<&Material::diffuseTransmission,
                       &scene::DiffuseTransmissionExtension::diffuseTransmissionColorTexture>},
}};
// clang-format on

// Row i describes TextureSlot(i), so the table can be indexed by slot.
constexpr bool rowsInSlotOrder() {
    for (std::uint32_t i = 0; i < kSlots.size(); ++i) {
        if (kSlots[i].slot != TextureSlot(i)) {
            return false;
        }
    }
    return true;
}
static_assert(rowsInSlotOrder(), "kSlots must list the texture slots in TextureSlot order.");

}  // namespace

std::span<const TextureSlotInfo, kMaterialTextureSlotCount> textureSlots() {
    return kSlots;
}

const TextureSlotInfo& textureSlotInfo(TextureSlot slot) {
    assert(std::uint32_t(slot) < kSlots.size());
    return kSlots[std::uint32_t(slot)];
}

std::optional<scene::TextureRef> slotTexture(const scene::Material& material, TextureSlot slot) {
    return textureSlotInfo(slot).texture(material);
}

ColorSpace slotColorSpace(const scene::Material& material, TextureSlot slot) {
    const TextureSlotInfo& info = textureSlotInfo(slot);
    return material.specularGlossiness ? info.specularGlossinessColorSpace : info.colorSpace;
}

bool SampledTextures::sampled(TextureSlot slot) const {
    return this->*textureSlotInfo(slot).sampled;
}

bool materialUsesTexcoord1(const scene::Material& material) {
    return std::any_of(kSlots.begin(), kSlots.end(), [&material](const TextureSlotInfo& info) {
        const TextureRefField& texture = info.texture(material);
        return texture && texture->texCoord == 1;
    });
}

bool materialShadesExtensions(const scene::Material& material) {
    return material.iridescence.has_value() || material.anisotropy.has_value() ||
           material.transmission.has_value() || material.diffuseTransmission.has_value();
}

bool materialUsesTangents(const scene::Material& material) {
    // Anisotropy turns the tangent even without a direction texture.
    return material.anisotropy.has_value() ||
           std::any_of(kSlots.begin(), kSlots.end(), [&material](const TextureSlotInfo& info) {
               return info.normalMap && info.texture(material).has_value();
           });
}

}  // namespace encore::render
