#include <gtest/gtest.h>

#include <set>
#include <string>

#include "render/MaterialSlots.h"

// The slot table on the CPU: which field each slot reads, its colour space, which switch
// uploads it. MaterialWgslTest checks the same table against material.wgsl.

namespace encore::render {
namespace {

scene::TextureRef textureRef(std::uint32_t texture) {
    scene::TextureRef ref;
    ref.texture = scene::TextureId{texture};
    return ref;
}

// A material with a texture in every slot: slot i reads texture i.
scene::Material everySlotTextured() {
    scene::Material material;
    material.baseColorTexture = textureRef(0);
    material.metallicRoughnessTexture = textureRef(1);
    material.normalTexture = textureRef(2);
    material.occlusionTexture = textureRef(3);
    material.emissiveTexture = textureRef(4);
    material.specular = scene::SpecularExtension{.specularTexture = textureRef(5),
                                                 .specularColorTexture = textureRef(6)};
    material.clearcoat = scene::ClearcoatExtension{.clearcoatTexture = textureRef(7),
                                                   .clearcoatRoughnessTexture = textureRef(8),
                                                   .clearcoatNormalTexture = textureRef(9)};
    material.sheen = scene::SheenExtension{.sheenColorTexture = textureRef(10),
                                           .sheenRoughnessTexture = textureRef(11)};
    material.iridescence = scene::IridescenceExtension{
        .iridescenceTexture = textureRef(12), .iridescenceThicknessTexture = textureRef(13)};
    material.anisotropy = scene::AnisotropyExtension{.anisotropyTexture = textureRef(14)};
    material.transmission = scene::TransmissionExtension{.transmissionTexture = textureRef(15)};
    material.volume = scene::VolumeExtension{.thicknessTexture = textureRef(16)};
    material.diffuseTransmission =
        scene::DiffuseTransmissionExtension{.diffuseTransmissionTexture = textureRef(17),
                                            .diffuseTransmissionColorTexture = textureRef(18)};
    return material;
}

TEST(MaterialSlotsTest, TheTableListsEverySlotInOrderWithNamesOfItsOwn) {
    const auto slots = textureSlots();
    ASSERT_EQ(slots.size(), kMaterialTextureSlotCount);
    std::set<std::string_view> names;
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
        EXPECT_EQ(slots[i].slot, TextureSlot(i));
        EXPECT_EQ(&textureSlotInfo(TextureSlot(i)), &slots[i]);
        EXPECT_TRUE(slots[i].textureName.ends_with("Texture")) << slots[i].textureName;
        EXPECT_TRUE(names.insert(slots[i].textureName).second) << slots[i].textureName;
        EXPECT_NE(slots[i].texture, nullptr);
        EXPECT_NE(slots[i].sampled, nullptr);
    }
    EXPECT_EQ(textureSlotInfo(TextureSlot::SheenRoughness).textureName, "sheenRoughnessTexture");
}

TEST(MaterialSlotsTest, EachSlotReadsItsOwnField) {
    const scene::Material material = everySlotTextured();
    for (std::uint32_t i = 0; i < kMaterialTextureSlotCount; ++i) {
        const auto texture = slotTexture(material, TextureSlot(i));
        ASSERT_TRUE(texture.has_value()) << "slot " << i;
        EXPECT_EQ(texture->texture.value, i) << "slot " << i;
    }
    // The accessors return the material's own references, not copies.
    EXPECT_EQ(&textureSlotInfo(TextureSlot::Occlusion).texture(material),
              &material.occlusionTexture);
    EXPECT_EQ(&textureSlotInfo(TextureSlot::ClearcoatNormal).texture(material),
              &material.clearcoat->clearcoatNormalTexture);
}

TEST(MaterialSlotsTest, ExtensionSlotsAreEmptyWithoutTheirExtension) {
    scene::Material material = everySlotTextured();
    material.specular.reset();
    material.clearcoat.reset();
    material.sheen.reset();
    material.iridescence.reset();
    material.anisotropy.reset();
    material.transmission.reset();
    material.volume.reset();
    material.diffuseTransmission.reset();
    for (std::uint32_t i = 0; i < kMaterialTextureSlotCount; ++i) {
        EXPECT_EQ(slotTexture(material, TextureSlot(i)).has_value(), i < 5) << "slot " << i;
    }
}

TEST(MaterialSlotsTest, SpecularGlossinessReplacesTheMetallicRoughnessTexture) {
    scene::Material material = everySlotTextured();
    material.specularGlossiness = scene::SpecularGlossinessExtension{};
    // The extension without a texture of its own hides the file's metallic-roughness fallback.
    EXPECT_FALSE(slotTexture(material, TextureSlot::MetallicRoughness).has_value());
    material.specularGlossiness->specularGlossinessTexture = textureRef(42);
    EXPECT_EQ(slotTexture(material, TextureSlot::MetallicRoughness)->texture.value, 42u);
}

TEST(MaterialSlotsTest, ColourDataIsSrgbAndTheSpecularGlossinessTextureToo) {
    scene::Material metallicRoughness;
    const std::set<TextureSlot> srgb = {TextureSlot::BaseColor, TextureSlot::Emissive,
                                        TextureSlot::SpecularColor, TextureSlot::SheenColor,
                                        TextureSlot::DiffuseTransmissionColor};
    for (std::uint32_t i = 0; i < kMaterialTextureSlotCount; ++i) {
        const TextureSlot slot = TextureSlot(i);
        EXPECT_EQ(slotColorSpace(metallicRoughness, slot),
                  srgb.contains(slot) ? ColorSpace::Srgb : ColorSpace::Linear)
            << "slot " << i;
    }
    scene::Material glossy;
    glossy.specularGlossiness = scene::SpecularGlossinessExtension{};
    for (std::uint32_t i = 0; i < kMaterialTextureSlotCount; ++i) {
        const TextureSlot slot = TextureSlot(i);
        const bool isSrgb = srgb.contains(slot) || slot == TextureSlot::MetallicRoughness;
        EXPECT_EQ(slotColorSpace(glossy, slot), isSrgb ? ColorSpace::Srgb : ColorSpace::Linear)
            << "slot " << i;
    }
}

TEST(MaterialSlotsTest, SampledTexturesSwitchTheirSlots) {
    const SampledTextures all = SampledTextures::all();
    const SampledTextures baseColorOnly = SampledTextures::baseColorOnly();
    SampledTextures noExtensions;
    noExtensions.extensions = false;
    SampledTextures noOcclusion;
    noOcclusion.occlusion = false;
    for (std::uint32_t i = 0; i < kMaterialTextureSlotCount; ++i) {
        const TextureSlot slot = TextureSlot(i);
        EXPECT_TRUE(all.sampled(slot)) << "slot " << i;
        EXPECT_EQ(baseColorOnly.sampled(slot), slot == TextureSlot::BaseColor) << "slot " << i;
        EXPECT_EQ(noExtensions.sampled(slot), i < 5) << "slot " << i;
        EXPECT_EQ(noOcclusion.sampled(slot), slot != TextureSlot::Occlusion) << "slot " << i;
    }
}

// Normal maps (base and clear coat) and anisotropy, with or without its direction texture, read
// the tangent frame.
TEST(MaterialSlotsTest, NormalMapsAndAnisotropyUseTangents) {
    scene::Material material;
    EXPECT_FALSE(materialUsesTangents(material));
    material.occlusionTexture = textureRef(0);
    material.clearcoat = scene::ClearcoatExtension{.clearcoatTexture = textureRef(1)};
    EXPECT_FALSE(materialUsesTangents(material));
    material.clearcoat->clearcoatNormalTexture = textureRef(2);
    EXPECT_TRUE(materialUsesTangents(material));
    material.clearcoat.reset();
    EXPECT_FALSE(materialUsesTangents(material));
    material.normalTexture = textureRef(3);
    EXPECT_TRUE(materialUsesTangents(material));
    material.normalTexture.reset();
    material.iridescence = scene::IridescenceExtension{.iridescenceTexture = textureRef(4)};
    EXPECT_FALSE(materialUsesTangents(material));
    material.anisotropy = scene::AnisotropyExtension{.anisotropyStrength = 0.5f};
    EXPECT_TRUE(materialUsesTangents(material));
    material.anisotropy->anisotropyTexture = textureRef(5);
    EXPECT_TRUE(materialUsesTangents(material));
}

}  // namespace
}  // namespace encore::render
