// Physically based material data: normal scale, occlusion strength and the KHR_materials_*
// extensions Encore shades (emissive_strength, unlit, ior, specular, clearcoat, sheen,
// pbrSpecularGlossiness), the ones it ignores, and the validation of every new field.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TestPaths.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::expectError;
using testing::loadGltf;
using testing::materialBuilder;

json& materialJson(test::GltfBuilder& builder) {
    return builder.json()["materials"][0];
}

void useExtension(test::GltfBuilder& builder, const std::string& name, bool required = false) {
    builder.json()["extensionsUsed"].push_back(name);
    if (required) {
        builder.json()["extensionsRequired"].push_back(name);
    }
}

// A texture reference with texCoord 1 and a KHR_texture_transform, to check that every
// extension slot honours both like the core slots do.
json transformedTexture(int index) {
    return {{"index", index},
            {"texCoord", 1},
            {"extensions",
             {{"KHR_texture_transform",
               {{"offset", {0.5, 0.25}}, {"rotation", 0.5}, {"scale", {2, 4}}}}}}};
}

void expectTransformed(const std::optional<TextureRef>& ref, std::uint32_t texture) {
    ASSERT_TRUE(ref.has_value());
    EXPECT_EQ(ref->texture.value, texture);
    EXPECT_EQ(ref->texCoord, 1u);
    ASSERT_TRUE(ref->transform.has_value());
    EXPECT_EQ(ref->transform->offset, glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(ref->transform->rotation, 0.5f);
    EXPECT_EQ(ref->transform->scale, glm::vec2(2, 4));
}

TEST(MaterialExtensionsTest, NormalScaleAndOcclusionStrength) {
    auto builder = materialBuilder();
    materialJson(builder)["normalTexture"] = {{"index", 0}, {"scale", 0.5}};
    materialJson(builder)["occlusionTexture"] = {{"index", 1}, {"strength", 0.25}};
    builder.addMaterial({});  // Material 1: neither texture.
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.normalTexture);
    EXPECT_EQ(material.normalTexture->texture.value, 0u);
    EXPECT_EQ(material.normalScale, 0.5f);
    ASSERT_TRUE(material.occlusionTexture);
    EXPECT_EQ(material.occlusionTexture->texture.value, 1u);
    EXPECT_EQ(material.occlusionStrength, 0.25f);
    EXPECT_EQ(scene->materials[1].normalScale, 1.0f);
    EXPECT_EQ(scene->materials[1].occlusionStrength, 1.0f);
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(MaterialExtensionsTest, DefaultsWithoutExtensions) {
    auto builder = materialBuilder();
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    EXPECT_EQ(material.emissiveStrength, 1.0f);
    EXPECT_FALSE(material.unlit);
    EXPECT_EQ(material.ior, 1.5f);
    EXPECT_FALSE(material.specular);
    EXPECT_FALSE(material.clearcoat);
    EXPECT_FALSE(material.sheen);
    EXPECT_FALSE(material.specularGlossiness);
    EXPECT_TRUE(material.ignoredExtensions.empty());
    EXPECT_TRUE(scene->extensionsUsed.empty());
    EXPECT_TRUE(scene->extensionsIgnored.empty());
}

TEST(MaterialExtensionsTest, EmissiveStrengthUnlitAndIor) {
    auto builder = materialBuilder();
    for (const char* name :
         {"KHR_materials_emissive_strength", "KHR_materials_unlit", "KHR_materials_ior"}) {
        useExtension(builder, name);
    }
    materialJson(builder)["emissiveFactor"] = {1, 0.5, 0};
    materialJson(builder)["extensions"] = {
        {"KHR_materials_emissive_strength", {{"emissiveStrength", 5.0}}},
        {"KHR_materials_unlit", json::object()},
        {"KHR_materials_ior", {{"ior", 1.33}}}};
    builder.addMaterial({});  // Material 1: an infinite ior and empty extension objects.
    builder.json()["materials"][1]["extensions"] = {
        {"KHR_materials_ior", {{"ior", 0}}}, {"KHR_materials_emissive_strength", json::object()}};
    builder.addMaterial({});  // Material 2: the ior extension without a value.
    builder.json()["materials"][2]["extensions"] = {{"KHR_materials_ior", json::object()}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    EXPECT_EQ(material.emissiveStrength, 5.0f);
    EXPECT_EQ(material.emissiveFactor, glm::vec3(1, 0.5f, 0));
    EXPECT_TRUE(material.unlit);
    EXPECT_FLOAT_EQ(material.ior, 1.33f);
    EXPECT_EQ(scene->materials[1].ior, 0.0f);
    EXPECT_EQ(scene->materials[1].emissiveStrength, 1.0f);
    EXPECT_FALSE(scene->materials[1].unlit);
    EXPECT_EQ(scene->materials[2].ior, 1.5f);
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(MaterialExtensionsTest, Specular) {
    auto builder = materialBuilder();
    useExtension(builder, "KHR_materials_specular");
    materialJson(builder)["extensions"]["KHR_materials_specular"] = {
        {"specularFactor", 0.25},
        {"specularTexture", transformedTexture(1)},
        {"specularColorFactor", {2.0, 0.5, 0.25}},
        {"specularColorTexture", {{"index", 2}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto& specular = scene->materials[0].specular;
    ASSERT_TRUE(specular);
    EXPECT_EQ(specular->specularFactor, 0.25f);
    expectTransformed(specular->specularTexture, 1);
    // Colour factors above 1 are allowed by the extension and kept.
    EXPECT_EQ(specular->specularColorFactor, glm::vec3(2.0f, 0.5f, 0.25f));
    ASSERT_TRUE(specular->specularColorTexture);
    EXPECT_EQ(specular->specularColorTexture->texture.value, 2u);
    EXPECT_EQ(specular->specularColorTexture->texCoord, 0u);
    EXPECT_FALSE(specular->specularColorTexture->transform);
}

TEST(MaterialExtensionsTest, Clearcoat) {
    auto builder = materialBuilder();
    useExtension(builder, "KHR_materials_clearcoat");
    materialJson(builder)["extensions"]["KHR_materials_clearcoat"] = {
        {"clearcoatFactor", 0.75},
        {"clearcoatTexture", {{"index", 0}}},
        {"clearcoatRoughnessFactor", 0.125},
        {"clearcoatRoughnessTexture", transformedTexture(1)},
        {"clearcoatNormalTexture", {{"index", 3}, {"scale", 0.5}, {"texCoord", 1}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto& clearcoat = scene->materials[0].clearcoat;
    ASSERT_TRUE(clearcoat);
    EXPECT_EQ(clearcoat->clearcoatFactor, 0.75f);
    ASSERT_TRUE(clearcoat->clearcoatTexture);
    EXPECT_EQ(clearcoat->clearcoatTexture->texture.value, 0u);
    EXPECT_EQ(clearcoat->clearcoatRoughnessFactor, 0.125f);
    expectTransformed(clearcoat->clearcoatRoughnessTexture, 1);
    ASSERT_TRUE(clearcoat->clearcoatNormalTexture);
    EXPECT_EQ(clearcoat->clearcoatNormalTexture->texture.value, 3u);
    EXPECT_EQ(clearcoat->clearcoatNormalTexture->texCoord, 1u);
    EXPECT_EQ(clearcoat->clearcoatNormalScale, 0.5f);
    // The clearcoat normal scale is its own: the base normal scale keeps its default.
    EXPECT_EQ(scene->materials[0].normalScale, 1.0f);
}

TEST(MaterialExtensionsTest, Sheen) {
    auto builder = materialBuilder();
    useExtension(builder, "KHR_materials_sheen");
    materialJson(builder)["extensions"]["KHR_materials_sheen"] = {
        {"sheenColorFactor", {0.5, 0.25, 1.0}},
        {"sheenColorTexture", transformedTexture(2)},
        {"sheenRoughnessFactor", 0.625},
        {"sheenRoughnessTexture", {{"index", 3}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto& sheen = scene->materials[0].sheen;
    ASSERT_TRUE(sheen);
    EXPECT_EQ(sheen->sheenColorFactor, glm::vec3(0.5f, 0.25f, 1.0f));
    expectTransformed(sheen->sheenColorTexture, 2);
    EXPECT_EQ(sheen->sheenRoughnessFactor, 0.625f);
    ASSERT_TRUE(sheen->sheenRoughnessTexture);
    EXPECT_EQ(sheen->sheenRoughnessTexture->texture.value, 3u);
}

TEST(MaterialExtensionsTest, EmptyExtensionObjectsTakeTheDefaults) {
    auto builder = materialBuilder();
    materialJson(builder)["extensions"] = {{"KHR_materials_specular", json::object()},
                                           {"KHR_materials_clearcoat", json::object()},
                                           {"KHR_materials_sheen", json::object()},
                                           {"KHR_materials_pbrSpecularGlossiness", json::object()}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.specular && material.clearcoat && material.sheen &&
                material.specularGlossiness);
    EXPECT_EQ(material.specular->specularFactor, 1.0f);
    EXPECT_EQ(material.specular->specularColorFactor, glm::vec3(1.0f));
    EXPECT_FALSE(material.specular->specularTexture);
    EXPECT_EQ(material.clearcoat->clearcoatFactor, 0.0f);
    EXPECT_EQ(material.clearcoat->clearcoatRoughnessFactor, 0.0f);
    EXPECT_EQ(material.clearcoat->clearcoatNormalScale, 1.0f);
    EXPECT_FALSE(material.clearcoat->clearcoatNormalTexture);
    EXPECT_EQ(material.sheen->sheenColorFactor, glm::vec3(0.0f));
    EXPECT_EQ(material.sheen->sheenRoughnessFactor, 0.0f);
    EXPECT_EQ(material.specularGlossiness->specularFactor, glm::vec3(1.0f));
    EXPECT_EQ(material.specularGlossiness->glossinessFactor, 1.0f);
    EXPECT_EQ(material.baseColorFactor, glm::vec4(1.0f));  // diffuseFactor's default.
    EXPECT_FALSE(material.baseColorTexture);
}

TEST(MaterialExtensionsTest, RequiredSpecularGlossinessLoads) {
    auto builder = materialBuilder();
    useExtension(builder, "KHR_materials_pbrSpecularGlossiness", true);
    // The metallic-roughness block is the fallback for viewers without the extension.
    materialJson(builder)["pbrMetallicRoughness"] = {{"baseColorFactor", {0, 0, 0, 1}},
                                                     {"baseColorTexture", {{"index", 3}}}};
    materialJson(builder)["extensions"]["KHR_materials_pbrSpecularGlossiness"] = {
        {"diffuseFactor", {0.5, 0.25, 0.125, 0.75}},
        {"diffuseTexture", transformedTexture(0)},
        {"specularFactor", {0.25, 0.5, 1.0}},
        {"glossinessFactor", 0.375},
        {"specularGlossinessTexture", {{"index", 2}, {"texCoord", 1}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    EXPECT_EQ(material.baseColorFactor, glm::vec4(0.5f, 0.25f, 0.125f, 0.75f));
    expectTransformed(material.baseColorTexture, 0);
    ASSERT_TRUE(material.specularGlossiness);
    EXPECT_EQ(material.specularGlossiness->specularFactor, glm::vec3(0.25f, 0.5f, 1.0f));
    EXPECT_EQ(material.specularGlossiness->glossinessFactor, 0.375f);
    ASSERT_TRUE(material.specularGlossiness->specularGlossinessTexture);
    EXPECT_EQ(material.specularGlossiness->specularGlossinessTexture->texture.value, 2u);
    EXPECT_EQ(material.specularGlossiness->specularGlossinessTexture->texCoord, 1u);
    EXPECT_EQ(scene->extensionsUsed,
              std::vector<std::string>{"KHR_materials_pbrSpecularGlossiness"});
    EXPECT_EQ(scene->extensionsRequired,
              std::vector<std::string>{"KHR_materials_pbrSpecularGlossiness"});
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(MaterialExtensionsTest, RequiredUnsupportedExtensionIsRefused) {
    auto builder = materialBuilder();
    useExtension(builder, "VENDOR_materials_custom", true);
    materialJson(builder)["extensions"]["VENDOR_materials_custom"] = {{"factor", 1.0}};
    expectError(
        loadGltf(builder), ErrorCode::Unsupported,
        {"test.gltf: ", "requires the extension VENDOR_materials_custom", "does not support"});
}

TEST(MaterialExtensionsTest, UnshadedExtensionsAreListedAndWarned) {
    auto builder = materialBuilder();
    const std::vector<std::string> ignored = {
        "KHR_materials_volume_scatter",
        "VENDOR_materials_custom",
    };
    for (const std::string& name : ignored) {
        useExtension(builder, name);
        materialJson(builder)["extensions"][name] = json::object();
    }
    useExtension(builder, "KHR_materials_clearcoat");
    useExtension(builder, "KHR_texture_basisu");
    materialJson(builder)["extensions"]["KHR_materials_clearcoat"] = {{"clearcoatFactor", 1.0}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    EXPECT_EQ(material.ignoredExtensions, ignored);  // Shaded ones are not listed.
    ASSERT_TRUE(material.clearcoat);
    EXPECT_EQ(material.clearcoat->clearcoatFactor, 1.0f);

    std::vector<std::string> expectedIgnored = ignored;
    expectedIgnored.push_back("KHR_texture_basisu");
    EXPECT_EQ(scene->extensionsIgnored, expectedIgnored);
    ASSERT_EQ(scene->extensionsUsed.size(), ignored.size() + 2);
    ASSERT_EQ(scene->warnings.size(), expectedIgnored.size());
    EXPECT_EQ(scene->warnings[0],
              "test.gltf: The asset uses KHR_materials_volume_scatter, which Encore does not "
              "implement; materials are drawn without it.");
    EXPECT_EQ(scene->warnings.back(),
              "test.gltf: The asset uses KHR_texture_basisu, which Encore does not implement; the "
              "asset is drawn without it.");
}

TEST(MaterialExtensionsTest, UnshadedExtensionIsAnErrorWhenStrict) {
    auto builder = materialBuilder();
    useExtension(builder, "VENDOR_materials_custom");
    materialJson(builder)["extensions"]["VENDOR_materials_custom"] = json::object();
    expectError(loadGltf(builder, {.strict = true}), ErrorCode::Unsupported,
                {"test.gltf: ", "VENDOR_materials_custom", "does not implement"});
}

TEST(MaterialExtensionsTest, TextureIndicesOfEverySlotAreChecked) {
    const std::vector<std::pair<std::string, std::string>> slots = {
        {"KHR_materials_specular", "specularTexture"},
        {"KHR_materials_specular", "specularColorTexture"},
        {"KHR_materials_clearcoat", "clearcoatTexture"},
        {"KHR_materials_clearcoat", "clearcoatRoughnessTexture"},
        {"KHR_materials_clearcoat", "clearcoatNormalTexture"},
        {"KHR_materials_sheen", "sheenColorTexture"},
        {"KHR_materials_sheen", "sheenRoughnessTexture"},
        {"KHR_materials_pbrSpecularGlossiness", "diffuseTexture"},
        {"KHR_materials_pbrSpecularGlossiness", "specularGlossinessTexture"},
        {"KHR_materials_transmission", "transmissionTexture"},
        {"KHR_materials_volume", "thicknessTexture"},
        {"KHR_materials_diffuse_transmission", "diffuseTransmissionTexture"},
        {"KHR_materials_diffuse_transmission", "diffuseTransmissionColorTexture"},
    };
    for (const auto& [extension, slot] : slots) {
        SCOPED_TRACE(extension + " " + slot);
        auto builder = materialBuilder(2);
        builder.addMaterial({});
        builder.json()["materials"][1]["extensions"][extension][slot] = {{"index", 7}};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"test.gltf: material 1 " + extension + " " + slot + " refers to texture 7",
                     "the asset has 2 textures"});
    }
}

TEST(MaterialExtensionsTest, MalformedFieldsNameTheMaterialAndField) {
    struct Case {
        const char* name;
        json extensions;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
        {"ExtensionNotAnObject",
         {{"KHR_materials_ior", 3}},
         {"material 0 has an invalid KHR_materials_ior extension", "got 3"}},
        {"IorBelowOne",
         {{"KHR_materials_ior", {{"ior", 0.5}}}},
         {"material 0 KHR_materials_ior has an invalid ior (0.5"}},
        {"IorNotANumber",
         {{"KHR_materials_ior", {{"ior", "glass"}}}},
         {"material 0 KHR_materials_ior", "'ior'", "\"glass\""}},
        {"NegativeEmissiveStrength",
         {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}},
         {"material 0 KHR_materials_emissive_strength", "emissiveStrength (-1"}},
        {"SpecularColorOfTwo",
         {{"KHR_materials_specular", {{"specularColorFactor", {1, 1}}}}},
         {"material 0 KHR_materials_specular", "'specularColorFactor'", "an array of 3 numbers"}},
        {"SpecularFactorString",
         {{"KHR_materials_specular", {{"specularFactor", "high"}}}},
         {"material 0 KHR_materials_specular", "'specularFactor'"}},
        {"SheenColorOfFour",
         {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1, 1, 1}}}}},
         {"material 0 KHR_materials_sheen", "'sheenColorFactor'"}},
        {"DiffuseFactorOfThree",
         {{"KHR_materials_pbrSpecularGlossiness", {{"diffuseFactor", {1, 1, 1}}}}},
         {"material 0 KHR_materials_pbrSpecularGlossiness", "'diffuseFactor'",
          "an array of 4 numbers"}},
        {"TextureInfoNotAnObject",
         {{"KHR_materials_clearcoat", {{"clearcoatTexture", 2}}}},
         {"material 0 KHR_materials_clearcoat", "'clearcoatTexture'", "an object"}},
        {"TextureInfoWithoutIndex",
         {{"KHR_materials_sheen", {{"sheenColorTexture", {{"texCoord", 1}}}}}},
         {"material 0 KHR_materials_sheen sheenColorTexture", "required 'index'"}},
        {"ClearcoatNormalScaleNotANumber",
         {{"KHR_materials_clearcoat",
           {{"clearcoatNormalTexture", {{"index", 0}, {"scale", "big"}}}}}},
         {"material 0 KHR_materials_clearcoat clearcoatNormalTexture", "'scale'"}},
        {"TransformOnExtensionTexture",
         {{"KHR_materials_specular",
           {{"specularTexture",
             {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {1}}}}}}}}}}},
         {"material 0 KHR_materials_specular specularTexture KHR_texture_transform", "'scale'"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        auto builder = materialBuilder();
        materialJson(builder)["extensions"] = c.extensions;
        const auto result = loadGltf(builder);
        ASSERT_FALSE(result.ok());
        EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat);
        for (const std::string& fragment : c.fragments) {
            EXPECT_NE(result.error().message.find(fragment), std::string::npos)
                << "missing '" << fragment << "' in: " << result.error().message;
        }
    }
}

TEST(MaterialExtensionsTest, NormalScaleOfWrongTypeIsAnError) {
    auto builder = materialBuilder();
    materialJson(builder)["normalTexture"] = {{"index", 0}, {"scale", "1"}};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"material 0 normalTexture", "'scale'"});
}

TEST(MaterialExtensionsTest, AlphaBlendModeTestSampleModel) {
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        GTEST_SKIP() << "The shared sample models (../shared/models) are absent; skipping.";
    }
    const auto path = *dir / "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb";
    auto scene = loadScene(path, {.decodeImages = false});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    // MatBed has normal and occlusion textures without scale or strength: both default to 1.
    const auto bed = std::find_if(scene->materials.begin(), scene->materials.end(),
                                  [](const Material& m) { return m.name == "MatBed"; });
    ASSERT_NE(bed, scene->materials.end());
    EXPECT_TRUE(bed->normalTexture.has_value());
    EXPECT_TRUE(bed->occlusionTexture.has_value());
    EXPECT_EQ(bed->normalScale, 1.0f);
    EXPECT_EQ(bed->occlusionStrength, 1.0f);
    for (const Material& material : scene->materials) {
        EXPECT_TRUE(material.ignoredExtensions.empty()) << material.name;
        EXPECT_FALSE(material.specularGlossiness) << material.name;
    }
    EXPECT_TRUE(scene->extensionsIgnored.empty());
}

}  // namespace
}  // namespace encore::scene
