// KHR_materials_transmission, KHR_materials_volume, KHR_materials_dispersion and
// KHR_materials_diffuse_transmission: parsing, the defaults of empty extension objects, and the
// errors of invalid values.

#include <gtest/gtest.h>

#include <limits>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TestPaths.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::loadGltf;
using testing::triangleBuilder;

constexpr const char* kDiffuse = "KHR_materials_diffuse_transmission";

test::GltfBuilder builderWith(const json& extensions, bool required = false) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["material"] = builder.addMaterial({});
    builder.json()["textures"].push_back(json::object());
    builder.json()["textures"].push_back(json::object());
    builder.json()["materials"][0]["extensions"] = extensions;
    for (const auto& [name, value] : extensions.items()) {
        builder.json()["extensionsUsed"].push_back(name);
        if (required) {
            builder.json()["extensionsRequired"].push_back(name);
        }
    }
    return builder;
}

TEST(TransmissionExtensionsTest, FactorsTexturesAndColourAreRead) {
    auto builder =
        builderWith({{"KHR_materials_transmission",
                      {{"transmissionFactor", 0.75}, {"transmissionTexture", {{"index", 1}}}}},
                     {"KHR_materials_volume",
                      {{"thicknessFactor", 2.5},
                       {"thicknessTexture", {{"index", 0}, {"texCoord", 1}}},
                       {"attenuationDistance", 0.125},
                       {"attenuationColor", {0.25, 0.5, 1.0}}}},
                     {"KHR_materials_dispersion", {{"dispersion", 0.5}}}},
                    true);
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.transmission);
    EXPECT_EQ(material.transmission->transmissionFactor, 0.75f);
    ASSERT_TRUE(material.transmission->transmissionTexture);
    EXPECT_EQ(material.transmission->transmissionTexture->texture.value, 1u);
    ASSERT_TRUE(material.volume);
    EXPECT_EQ(material.volume->thicknessFactor, 2.5f);
    ASSERT_TRUE(material.volume->thicknessTexture);
    EXPECT_EQ(material.volume->thicknessTexture->texture.value, 0u);
    EXPECT_EQ(material.volume->thicknessTexture->texCoord, 1u);
    EXPECT_EQ(material.volume->attenuationDistance, 0.125f);
    EXPECT_EQ(material.volume->attenuationColor, glm::vec3(0.25f, 0.5f, 1.0f));
    ASSERT_TRUE(material.dispersion);
    EXPECT_EQ(material.dispersion->dispersion, 0.5f);
    // Shaded, so required is fine and nothing is reported as ignored.
    EXPECT_TRUE(material.ignoredExtensions.empty());
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(TransmissionExtensionsTest, EmptyObjectsGiveTheDefaults) {
    auto builder = builderWith({{"KHR_materials_transmission", json::object()},
                                {"KHR_materials_volume", json::object()},
                                {"KHR_materials_dispersion", json::object()}});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.transmission && material.volume && material.dispersion);
    EXPECT_EQ(material.transmission->transmissionFactor, 0.0f);
    EXPECT_FALSE(material.transmission->transmissionTexture);
    EXPECT_EQ(material.volume->thicknessFactor, 0.0f);
    EXPECT_FALSE(material.volume->thicknessTexture);
    EXPECT_EQ(material.volume->attenuationDistance, std::numeric_limits<float>::infinity());
    EXPECT_EQ(material.volume->attenuationColor, glm::vec3(1.0f));
    EXPECT_EQ(material.dispersion->dispersion, 0.0f);
}

TEST(TransmissionExtensionsTest, AbsentExtensionsStayAbsent) {
    auto builder = builderWith(json::object());
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_FALSE(scene->materials[0].transmission);
    EXPECT_FALSE(scene->materials[0].volume);
    EXPECT_FALSE(scene->materials[0].dispersion);
}

TEST(TransmissionExtensionsTest, DiffuseTransmissionFactorsAndTexturesAreRead) {
    auto builder =
        builderWith({{kDiffuse,
                      {{"diffuseTransmissionFactor", 0.75},
                       {"diffuseTransmissionTexture", {{"index", 0}}},
                       {"diffuseTransmissionColorFactor", {1.0, 0.5, 0.25}},
                       {"diffuseTransmissionColorTexture",
                        {{"index", 1},
                         {"texCoord", 1},
                         {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}}}}}}}},
                    true);
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.diffuseTransmission);
    const DiffuseTransmissionExtension& diffuse = *material.diffuseTransmission;
    EXPECT_EQ(diffuse.diffuseTransmissionFactor, 0.75f);
    ASSERT_TRUE(diffuse.diffuseTransmissionTexture);
    EXPECT_EQ(diffuse.diffuseTransmissionTexture->texture.value, 0u);
    EXPECT_EQ(diffuse.diffuseTransmissionTexture->texCoord, 0u);
    EXPECT_EQ(diffuse.diffuseTransmissionColorFactor, glm::vec3(1.0f, 0.5f, 0.25f));
    ASSERT_TRUE(diffuse.diffuseTransmissionColorTexture);
    EXPECT_EQ(diffuse.diffuseTransmissionColorTexture->texture.value, 1u);
    EXPECT_EQ(diffuse.diffuseTransmissionColorTexture->texCoord, 1u);
    ASSERT_TRUE(diffuse.diffuseTransmissionColorTexture->transform);
    EXPECT_EQ(diffuse.diffuseTransmissionColorTexture->transform->offset, glm::vec2(0.5f, 0.0f));
    EXPECT_FALSE(material.transmission);
    // Shaded: a file that requires it loads, and nothing is reported as ignored.
    EXPECT_TRUE(material.ignoredExtensions.empty());
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(TransmissionExtensionsTest, DiffuseTransmissionDefaultsAndItsVolume) {
    auto builder = builderWith({{kDiffuse, json::object()}});
    builder.addMaterial({});  // Material 1: without the extension.
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_TRUE(scene->materials[0].diffuseTransmission);
    const DiffuseTransmissionExtension& diffuse = *scene->materials[0].diffuseTransmission;
    EXPECT_EQ(diffuse.diffuseTransmissionFactor, 0.0f);
    EXPECT_FALSE(diffuse.diffuseTransmissionTexture);
    EXPECT_EQ(diffuse.diffuseTransmissionColorFactor, glm::vec3(1.0f));
    EXPECT_FALSE(diffuse.diffuseTransmissionColorTexture);
    EXPECT_FALSE(scene->materials[1].diffuseTransmission);

    // A volume may accompany diffuse transmission instead of transmission.
    auto withVolume = builderWith(
        {{kDiffuse, {{"diffuseTransmissionFactor", 1.0}}},
         {"KHR_materials_volume", {{"thicknessFactor", 0.5}, {"attenuationColor", {0.5, 1, 1}}}}});
    auto volumeScene = loadGltf(withVolume);
    ASSERT_TRUE(volumeScene.ok()) << volumeScene.error().message;
    const Material& material = volumeScene->materials[0];
    ASSERT_TRUE(material.diffuseTransmission && material.volume);
    EXPECT_EQ(material.volume->thicknessFactor, 0.5f);
    EXPECT_TRUE(volumeScene->warnings.empty());
}

TEST(TransmissionExtensionsTest, InvalidValuesNameTheMaterialAndField) {
    struct Case {
        std::string name;
        json extensions;
        std::vector<std::string> expected;
    };
    const std::vector<Case> cases = {
        {"TransmissionAboveOne",
         {{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}},
         {"material 0 KHR_materials_transmission has an invalid transmissionFactor (1.5",
          "it must lie in [0, 1]"}},
        {"TransmissionNegative",
         {{"KHR_materials_transmission", {{"transmissionFactor", -0.25}}}},
         {"transmissionFactor (-0.25"}},
        {"TransmissionNotANumber",
         {{"KHR_materials_transmission", {{"transmissionFactor", "clear"}}}},
         {"material 0 KHR_materials_transmission", "'transmissionFactor'"}},
        {"NegativeThickness",
         {{"KHR_materials_volume", {{"thicknessFactor", -1}}}},
         {"material 0 KHR_materials_volume has an invalid thicknessFactor (-1", "at least 0"}},
        {"ZeroAttenuationDistance",
         {{"KHR_materials_volume", {{"attenuationDistance", 0}}}},
         {"material 0 KHR_materials_volume has an invalid attenuationDistance (0",
          "greater than 0"}},
        {"AttenuationColorOfTwo",
         {{"KHR_materials_volume", {{"attenuationColor", {1, 1}}}}},
         {"material 0 KHR_materials_volume", "'attenuationColor'"}},
        {"AttenuationColorAboveOne",
         {{"KHR_materials_volume", {{"attenuationColor", {0.5, 2, 0.5}}}}},
         {"material 0 KHR_materials_volume has an invalid attenuationColor (component 1 is 2"}},
        {"NegativeDispersion",
         {{"KHR_materials_dispersion", {{"dispersion", -0.5}}}},
         {"material 0 KHR_materials_dispersion has an invalid dispersion (-0.5", "at least 0"}},
        {"ThicknessTextureOutOfRange",
         {{"KHR_materials_volume", {{"thicknessTexture", {{"index", 9}}}}}},
         {"material 0 KHR_materials_volume thicknessTexture refers to texture 9"}},
        {"TransmissionNotAnObject",
         {{"KHR_materials_transmission", 1}},
         {"material 0 has an invalid KHR_materials_transmission extension"}},
        {"DiffuseTransmissionAboveOne",
         {{kDiffuse, {{"diffuseTransmissionFactor", 1.5}}}},
         {"material 0 KHR_materials_diffuse_transmission has an invalid "
          "diffuseTransmissionFactor (1.5",
          "it must lie in [0, 1]"}},
        {"DiffuseTransmissionNegative",
         {{kDiffuse, {{"diffuseTransmissionFactor", -0.5}}}},
         {"diffuseTransmissionFactor (-0.5"}},
        {"DiffuseTransmissionNotANumber",
         {{kDiffuse, {{"diffuseTransmissionFactor", "half"}}}},
         {"material 0 KHR_materials_diffuse_transmission", "'diffuseTransmissionFactor'"}},
        {"DiffuseTransmissionColorOfTwo",
         {{kDiffuse, {{"diffuseTransmissionColorFactor", {1, 1}}}}},
         {"material 0 KHR_materials_diffuse_transmission", "'diffuseTransmissionColorFactor'"}},
        {"DiffuseTransmissionColorAboveOne",
         {{kDiffuse, {{"diffuseTransmissionColorFactor", {0.5, 0.5, 3}}}}},
         {"has an invalid diffuseTransmissionColorFactor (component 2 is 3",
          "each must be between 0 and 1"}},
        {"DiffuseTransmissionTextureWithoutIndex",
         {{kDiffuse, {{"diffuseTransmissionTexture", json::object()}}}},
         {"material 0 KHR_materials_diffuse_transmission diffuseTransmissionTexture", "'index'"}},
        {"DiffuseTransmissionColorTextureOutOfRange",
         {{kDiffuse, {{"diffuseTransmissionColorTexture", {{"index", 9}}}}}},
         {"material 0 KHR_materials_diffuse_transmission diffuseTransmissionColorTexture refers "
          "to texture 9"}},
        {"DiffuseTransmissionNotAnObject",
         {{kDiffuse, 1}},
         {"material 0 has an invalid KHR_materials_diffuse_transmission extension"}},
    };
    for (const Case& entry : cases) {
        SCOPED_TRACE(entry.name);
        auto builder = builderWith(entry.extensions);
        const auto loaded = loadGltf(builder);
        ASSERT_FALSE(loaded.ok());
        EXPECT_EQ(loaded.error().code, ErrorCode::InvalidFormat);
        EXPECT_EQ(loaded.error().message.rfind("test.gltf: ", 0), 0u) << loaded.error().message;
        for (const std::string& fragment : entry.expected) {
            EXPECT_NE(loaded.error().message.find(fragment), std::string::npos)
                << "missing '" << fragment << "' in: " << loaded.error().message;
        }
    }
}

}  // namespace
}  // namespace encore::scene
