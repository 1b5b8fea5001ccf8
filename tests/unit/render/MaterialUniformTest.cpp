#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "render/MaterialUniform.h"

// makeMaterialUniform on the CPU: each scene::Material field lands in its place of the
// MaterialUniform (material.wgsl's `Material`), with the values the shader expects.

namespace encore::render {
namespace {

scene::TextureRef textureRef(std::uint32_t texture, std::uint32_t texCoord = 0) {
    scene::TextureRef ref;
    ref.texture = scene::TextureId{texture};
    ref.texCoord = texCoord;
    return ref;
}

void expectVector(const float (&actual)[4],
                  float x,
                  float y,
                  float z,
                  float w,
                  const std::string& what) {
    EXPECT_FLOAT_EQ(actual[0], x) << what << "[0]";
    EXPECT_FLOAT_EQ(actual[1], y) << what << "[1]";
    EXPECT_FLOAT_EQ(actual[2], z) << what << "[2]";
    EXPECT_FLOAT_EQ(actual[3], w) << what << "[3]";
}

// The identity transform, reading TEXCOORD_0.
void expectIdentitySlot(const TextureSlotUniform& slot, const std::string& what) {
    expectVector(slot.row0, 1.0f, 0.0f, 0.0f, 0.0f, what + " row0");
    expectVector(slot.row1, 0.0f, 1.0f, 0.0f, 0.0f, what + " row1");
}

TEST(MaterialUniformTest, TheDefaultMaterialPacksTheGltfDefaults) {
    const MaterialUniform uniform = makeMaterialUniform(scene::Material{});
    expectVector(uniform.baseColorFactor, 1.0f, 1.0f, 1.0f, 1.0f, "baseColorFactor");
    expectVector(uniform.emissive, 0.0f, 0.0f, 0.0f, 0.0f, "emissive");
    expectVector(uniform.metallicRoughness, 1.0f, 1.0f, 1.0f, 1.0f, "metallicRoughness");
    // Opaque: no cutoff, no blending; IOR 1.5.
    expectVector(uniform.alpha, 0.0f, 0.0f, 1.5f, 0.0f, "alpha");
    // Without KHR_materials_specular the specular lobe is the plain dielectric one.
    expectVector(uniform.specular, 1.0f, 1.0f, 1.0f, 1.0f, "specular");
    expectVector(uniform.clearcoat, 0.0f, 0.0f, 0.0f, 0.0f, "clearcoat");
    expectVector(uniform.sheen, 0.0f, 0.0f, 0.0f, 0.0f, "sheen");
    expectVector(uniform.specularGlossiness, 0.0f, 0.0f, 0.0f, 0.0f, "specularGlossiness");
    EXPECT_EQ(uniform.flags[0], std::uint32_t(ShadingModel::MetallicRoughness));
    EXPECT_EQ(uniform.flags[1], 0u);
    EXPECT_EQ(uniform.flags[2], 0u);
    EXPECT_EQ(uniform.flags[3], 0u);
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        expectIdentitySlot(uniform.slots[slot], "slot " + std::to_string(slot));
    }
}

TEST(MaterialUniformTest, CoreFactorsLandInTheirVectors) {
    scene::Material material;
    material.baseColorFactor = {0.25f, 0.5f, 0.75f, 0.125f};
    material.emissiveFactor = {0.5f, 0.25f, 1.0f};
    material.emissiveStrength = 4.0f;
    material.metallicFactor = 0.3f;
    material.roughnessFactor = 0.6f;
    material.normalScale = 0.8f;
    material.occlusionStrength = 0.9f;
    material.ior = 1.33f;
    const MaterialUniform uniform = makeMaterialUniform(material);
    expectVector(uniform.baseColorFactor, 0.25f, 0.5f, 0.75f, 0.125f, "baseColorFactor");
    // emissiveFactor * KHR_materials_emissive_strength.
    expectVector(uniform.emissive, 2.0f, 1.0f, 4.0f, 0.0f, "emissive");
    expectVector(uniform.metallicRoughness, 0.3f, 0.6f, 0.8f, 0.9f, "metallicRoughness");
    expectVector(uniform.alpha, 0.0f, 0.0f, 1.33f, 0.0f, "alpha");
    // Factors alone switch no feature: the bits follow extensions and normal maps.
    EXPECT_EQ(uniform.flags[1], 0u);
}

TEST(MaterialUniformTest, TheAlphaCutoffIsWrittenForMaskOnly) {
    scene::Material material;
    material.alphaCutoff = 0.3f;
    material.alphaMode = scene::AlphaMode::Opaque;
    expectVector(makeMaterialUniform(material).alpha, 0.0f, 0.0f, 1.5f, 0.0f, "opaque");
    material.alphaMode = scene::AlphaMode::Blend;
    expectVector(makeMaterialUniform(material).alpha, 0.0f, 1.0f, 1.5f, 0.0f, "blend");
    material.alphaMode = scene::AlphaMode::Mask;
    expectVector(makeMaterialUniform(material).alpha, 0.3f, 0.0f, 1.5f, 0.0f, "mask");
    // A cutoff of 0 stays 0 (everything passes), not the default 0.5.
    material.alphaCutoff = 0.0f;
    expectVector(makeMaterialUniform(material).alpha, 0.0f, 0.0f, 1.5f, 0.0f, "mask at 0");
}

TEST(MaterialUniformTest, ExtensionsWriteTheirFactorsAndFeatureBits) {
    scene::Material material;
    material.specular =
        scene::SpecularExtension{.specularFactor = 0.4f, .specularColorFactor = {0.1f, 0.2f, 0.3f}};
    material.clearcoat = scene::ClearcoatExtension{
        .clearcoatFactor = 0.7f, .clearcoatRoughnessFactor = 0.2f, .clearcoatNormalScale = 0.5f};
    material.sheen =
        scene::SheenExtension{.sheenColorFactor = {0.9f, 0.8f, 0.7f}, .sheenRoughnessFactor = 0.6f};
    MaterialUniform uniform = makeMaterialUniform(material);
    expectVector(uniform.specular, 0.1f, 0.2f, 0.3f, 0.4f, "specular");
    expectVector(uniform.clearcoat, 0.7f, 0.2f, 0.5f, 0.0f, "clearcoat");
    expectVector(uniform.sheen, 0.9f, 0.8f, 0.7f, 0.6f, "sheen");
    EXPECT_EQ(uniform.flags[1], kMaterialSpecular | kMaterialClearcoat | kMaterialSheen);
    EXPECT_EQ(uniform.flags[0], std::uint32_t(ShadingModel::MetallicRoughness));

    // Normal maps switch their own bits; the clear coat's only within the extension.
    material.normalTexture = textureRef(0);
    material.clearcoat->clearcoatNormalTexture = textureRef(1);
    uniform = makeMaterialUniform(material);
    EXPECT_EQ(uniform.flags[1], 31u);
    EXPECT_EQ(uniform.flags[1], kMaterialNormalMap | kMaterialClearcoatNormalMap |
                                    kMaterialClearcoat | kMaterialSheen | kMaterialSpecular);

    scene::Material normalOnly;
    normalOnly.normalTexture = textureRef(0);
    EXPECT_EQ(makeMaterialUniform(normalOnly).flags[1], kMaterialNormalMap);
}

TEST(MaterialUniformTest, TransmissionVolumeAndDispersionPackTogether) {
    scene::Material material;
    MaterialUniform uniform = makeMaterialUniform(material);
    expectVector(uniform.transmission, 0.0f, 0.0f, 0.0f, 0.0f, "no transmission");
    expectVector(uniform.attenuationColor, 1.0f, 1.0f, 1.0f, 0.0f, "no attenuation");
    EXPECT_EQ(uniform.flags[1] & (kMaterialTransmission | kMaterialVolume), 0u);

    // Volume and dispersion without transmission have nothing to act on.
    material.volume = scene::VolumeExtension{.thicknessFactor = 2.0f};
    material.dispersion = scene::DispersionExtension{.dispersion = 0.5f};
    uniform = makeMaterialUniform(material);
    expectVector(uniform.transmission, 0.0f, 0.0f, 0.0f, 0.0f, "volume alone");
    EXPECT_EQ(uniform.flags[1], 0u);

    material.transmission = scene::TransmissionExtension{.transmissionFactor = 0.75f};
    uniform = makeMaterialUniform(material);
    // An infinite attenuation distance (the default) is written as 0: no absorption.
    expectVector(uniform.transmission, 0.75f, 2.0f, 0.0f, 0.5f, "transmission and volume");
    EXPECT_EQ(uniform.flags[1], kMaterialTransmission | kMaterialVolume);

    material.volume->attenuationDistance = 0.25f;
    material.volume->attenuationColor = {0.1f, 0.2f, 0.3f};
    uniform = makeMaterialUniform(material);
    expectVector(uniform.transmission, 0.75f, 2.0f, 0.25f, 0.5f, "attenuation distance");
    expectVector(uniform.attenuationColor, 0.1f, 0.2f, 0.3f, 0.0f, "attenuation colour");

    // Dispersion needs a volume to spread through.
    material.volume.reset();
    uniform = makeMaterialUniform(material);
    expectVector(uniform.transmission, 0.75f, 0.0f, 0.0f, 0.0f, "thin-walled");
    EXPECT_EQ(uniform.flags[1], kMaterialTransmission);
}

TEST(MaterialUniformTest, DiffuseTransmissionPacksColourFactorAndVolume) {
    scene::Material material;
    MaterialUniform uniform = makeMaterialUniform(material);
    expectVector(uniform.diffuseTransmission, 0.0f, 0.0f, 0.0f, 0.0f, "none");
    EXPECT_EQ(uniform.flags[1] & kMaterialDiffuseTransmission, 0u);

    material.diffuseTransmission = scene::DiffuseTransmissionExtension{
        .diffuseTransmissionFactor = 0.75f, .diffuseTransmissionColorFactor = {1.0f, 0.5f, 0.25f}};
    uniform = makeMaterialUniform(material);
    expectVector(uniform.diffuseTransmission, 1.0f, 0.5f, 0.25f, 0.75f, "factors");
    EXPECT_EQ(uniform.flags[1], kMaterialDiffuseTransmission);
    expectVector(uniform.transmission, 0.0f, 0.0f, 0.0f, 0.0f, "no volume");

    // A volume acts through diffuse transmission too (thickness and absorption), but
    // transmission stays off and dispersion has nothing to spread.
    material.volume = scene::VolumeExtension{.thicknessFactor = 2.0f,
                                             .attenuationDistance = 0.5f,
                                             .attenuationColor = {0.1f, 0.2f, 0.3f}};
    material.dispersion = scene::DispersionExtension{.dispersion = 0.5f};
    uniform = makeMaterialUniform(material);
    expectVector(uniform.transmission, 0.0f, 2.0f, 0.5f, 0.0f, "volume");
    expectVector(uniform.attenuationColor, 0.1f, 0.2f, 0.3f, 0.0f, "attenuation colour");
    EXPECT_EQ(uniform.flags[1], kMaterialDiffuseTransmission | kMaterialVolume);

    // Its textures are slots of their own, read through the palette like any other.
    material.diffuseTransmission->diffuseTransmissionTexture = textureRef(0);
    material.diffuseTransmission->diffuseTransmissionColorTexture = textureRef(1);
    SlotSamplerEntries entries{};
    entries[std::uint32_t(TextureSlot::DiffuseTransmissionColor)] = 2;
    uniform = makeMaterialUniform(material, entries);
    EXPECT_EQ(uniform.slots[std::uint32_t(TextureSlot::DiffuseTransmissionColor)].row1[3], 2.0f);
    EXPECT_EQ(slotTexture(material, TextureSlot::DiffuseTransmission)->texture.value, 0u);
    EXPECT_EQ(slotColorSpace(material, TextureSlot::DiffuseTransmission), ColorSpace::Linear);
    EXPECT_EQ(slotColorSpace(material, TextureSlot::DiffuseTransmissionColor), ColorSpace::Srgb);
}

TEST(MaterialUniformTest, ShadingModelFollowsSpecularGlossinessAndUnlit) {
    scene::Material glossy;
    glossy.specularGlossiness = scene::SpecularGlossinessExtension{
        .specularFactor = {0.2f, 0.4f, 0.6f}, .glossinessFactor = 0.8f};
    MaterialUniform uniform = makeMaterialUniform(glossy);
    EXPECT_EQ(uniform.flags[0], 1u);
    EXPECT_EQ(uniform.flags[0], std::uint32_t(ShadingModel::SpecularGlossiness));
    expectVector(uniform.specularGlossiness, 0.2f, 0.4f, 0.6f, 0.8f, "specularGlossiness");
    EXPECT_EQ(uniform.flags[1], 0u);

    scene::Material unlit;
    unlit.unlit = true;
    EXPECT_EQ(makeMaterialUniform(unlit).flags[0], 2u);
    EXPECT_EQ(makeMaterialUniform(unlit).flags[0], std::uint32_t(ShadingModel::Unlit));

    // KHR_materials_unlit wins; the specular-glossiness factors are still written.
    glossy.unlit = true;
    uniform = makeMaterialUniform(glossy);
    EXPECT_EQ(uniform.flags[0], std::uint32_t(ShadingModel::Unlit));
    expectVector(uniform.specularGlossiness, 0.2f, 0.4f, 0.6f, 0.8f, "unlit specularGlossiness");
}

TEST(MaterialUniformTest, TextureTransformsAreTheRowsOfTranslateRotateScale) {
    scene::Material material;
    material.emissiveTexture = textureRef(0);
    material.emissiveTexture->transform =
        scene::TextureTransform{{0.5f, 0.25f}, std::numbers::pi_v<float> / 2.0f, {2.0f, 3.0f}};
    material.baseColorTexture = textureRef(1);
    material.baseColorTexture->transform =
        scene::TextureTransform{{0.125f, 0.75f}, 0.0f, {4.0f, 0.5f}};
    const MaterialUniform uniform = makeMaterialUniform(material);

    // T(0.5, 0.25) * R(pi/2) * S(2, 3) with KHR_texture_transform's R = [cos sin; -sin cos]:
    // u' = 3v + 0.5, v' = -2u + 0.25.
    const TextureSlotUniform& emissive = uniform.slots[std::uint32_t(TextureSlot::Emissive)];
    EXPECT_NEAR(emissive.row0[0], 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(emissive.row0[1], 3.0f);
    EXPECT_FLOAT_EQ(emissive.row0[2], 0.5f);
    EXPECT_EQ(emissive.row0[3], 0.0f);
    EXPECT_FLOAT_EQ(emissive.row1[0], -2.0f);
    EXPECT_NEAR(emissive.row1[1], 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(emissive.row1[2], 0.25f);
    EXPECT_EQ(emissive.row1[3], 0.0f);

    // No rotation: scale on the diagonal, offset in the third column.
    const TextureSlotUniform& base = uniform.slots[std::uint32_t(TextureSlot::BaseColor)];
    expectVector(base.row0, 4.0f, 0.0f, 0.125f, 0.0f, "base colour row0");
    expectVector(base.row1, 0.0f, 0.5f, 0.75f, 0.0f, "base colour row1");

    // A texture without a transform, and an empty slot, get the identity.
    expectIdentitySlot(uniform.slots[std::uint32_t(TextureSlot::Normal)], "normal");
}

TEST(MaterialUniformTest, TexCoord1IsMarkedPerSlot) {
    scene::Material material;
    material.occlusionTexture = textureRef(0, 1);
    material.baseColorTexture = textureRef(1, 0);
    material.clearcoat = scene::ClearcoatExtension{};
    material.clearcoat->clearcoatRoughnessTexture = textureRef(2, 1);
    const MaterialUniform uniform = makeMaterialUniform(material);
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        const bool second = TextureSlot(slot) == TextureSlot::Occlusion ||
                            TextureSlot(slot) == TextureSlot::ClearcoatRoughness;
        EXPECT_EQ(uniform.slots[slot].row0[3], second ? 1.0f : 0.0f) << "slot " << slot;
        EXPECT_EQ(uniform.slots[slot].row1[3], 0.0f) << "slot " << slot;
    }
    EXPECT_TRUE(materialUsesTexcoord1(material));
    material.occlusionTexture->texCoord = 0;
    material.clearcoat->clearcoatRoughnessTexture->texCoord = 0;
    EXPECT_FALSE(materialUsesTexcoord1(material));
}

// Under KHR_materials_pbrSpecularGlossiness the metallic-roughness slot reads the
// specular-glossiness texture, transform and texCoord included.
TEST(MaterialUniformTest, TheSpecularGlossinessTextureFillsTheMetallicRoughnessSlot) {
    scene::Material material;
    material.metallicRoughnessTexture = textureRef(0, 0);  // The file's fallback.
    material.specularGlossiness = scene::SpecularGlossinessExtension{};
    material.specularGlossiness->specularGlossinessTexture = textureRef(1, 1);
    material.specularGlossiness->specularGlossinessTexture->transform =
        scene::TextureTransform{{0.25f, 0.5f}, 0.0f, {1.0f, 1.0f}};
    const MaterialUniform uniform = makeMaterialUniform(material);
    const TextureSlotUniform& slot = uniform.slots[std::uint32_t(TextureSlot::MetallicRoughness)];
    expectVector(slot.row0, 1.0f, 0.0f, 0.25f, 1.0f, "row0");
    expectVector(slot.row1, 0.0f, 1.0f, 0.5f, 0.0f, "row1");
}

// Each slot's sampler palette entry (SamplerPalette.h) lands in row1[3].
TEST(MaterialUniformTest, EachSlotCarriesItsSamplerPaletteEntry) {
    scene::Material material;
    material.baseColorTexture = textureRef(0);
    material.emissiveTexture = textureRef(1);
    SlotSamplerEntries entries{};
    entries[std::uint32_t(TextureSlot::Emissive)] = 3;
    entries[std::uint32_t(TextureSlot::Normal)] = 1;
    const MaterialUniform uniform = makeMaterialUniform(material, entries);
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        EXPECT_EQ(uniform.slots[slot].row1[3], float(entries[slot])) << "slot " << slot;
    }
}

TEST(MaterialUniformTest, IridescenceAndAnisotropyFactorsAndBits) {
    scene::Material material;
    EXPECT_EQ(makeMaterialUniform(material).flags[1] &
                  (kMaterialIridescence | kMaterialAnisotropy | kMaterialAnisotropyTexture),
              0u);
    material.iridescence = scene::IridescenceExtension{.iridescenceFactor = 0.5f,
                                                       .iridescenceIor = 1.8f,
                                                       .iridescenceThicknessMinimum = 200.0f,
                                                       .iridescenceThicknessMaximum = 600.0f};
    material.anisotropy = scene::AnisotropyExtension{
        .anisotropyStrength = 0.25f, .anisotropyRotation = std::numbers::pi_v<float> / 2.0f};
    MaterialUniform uniform = makeMaterialUniform(material);
    expectVector(uniform.iridescence, 0.5f, 1.8f, 200.0f, 600.0f, "iridescence");
    EXPECT_NEAR(uniform.anisotropy[0], 0.0f, 1e-6f);  // cos(pi / 2)
    EXPECT_FLOAT_EQ(uniform.anisotropy[1], 1.0f);     // sin(pi / 2)
    EXPECT_EQ(uniform.anisotropy[2], 0.25f);
    EXPECT_EQ(uniform.flags[1], kMaterialIridescence | kMaterialAnisotropy);
    material.anisotropy->anisotropyTexture = textureRef(0);
    uniform = makeMaterialUniform(material);
    EXPECT_EQ(uniform.flags[1],
              kMaterialIridescence | kMaterialAnisotropy | kMaterialAnisotropyTexture);
}

}  // namespace
}  // namespace encore::render
