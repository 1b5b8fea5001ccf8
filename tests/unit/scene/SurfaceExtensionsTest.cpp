// The surface-layer material extensions: KHR_materials_iridescence (a thin film) and
// KHR_materials_anisotropy (a stretched specular lobe): parsing, defaults, required use, texture
// validation and errors naming the material, the extension and the field.

#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::expectError;
using testing::loadGltf;
using testing::materialBuilder;

json& extensionsOf(test::GltfBuilder& builder) {
    return builder.json()["materials"][0]["extensions"];
}

TEST(SurfaceExtensionsTest, Iridescence) {
    auto builder = materialBuilder();
    builder.json()["extensionsUsed"].push_back("KHR_materials_iridescence");
    extensionsOf(builder)["KHR_materials_iridescence"] = {
        {"iridescenceFactor", 0.75},
        {"iridescenceTexture", {{"index", 1}}},
        {"iridescenceIor", 1.8},
        {"iridescenceThicknessMinimum", 200},
        {"iridescenceThicknessMaximum", 600},
        {"iridescenceThicknessTexture", {{"index", 2}, {"texCoord", 1}}},
    };
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.iridescence.has_value());
    const IridescenceExtension& film = *material.iridescence;
    EXPECT_EQ(film.iridescenceFactor, 0.75f);
    ASSERT_TRUE(film.iridescenceTexture.has_value());
    EXPECT_EQ(film.iridescenceTexture->texture.value, 1u);
    EXPECT_FLOAT_EQ(film.iridescenceIor, 1.8f);
    EXPECT_EQ(film.iridescenceThicknessMinimum, 200.0f);
    EXPECT_EQ(film.iridescenceThicknessMaximum, 600.0f);
    ASSERT_TRUE(film.iridescenceThicknessTexture.has_value());
    EXPECT_EQ(film.iridescenceThicknessTexture->texture.value, 2u);
    EXPECT_EQ(film.iridescenceThicknessTexture->texCoord, 1u);
    EXPECT_TRUE(material.ignoredExtensions.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(SurfaceExtensionsTest, Anisotropy) {
    auto builder = materialBuilder();
    builder.json()["extensionsUsed"].push_back("KHR_materials_anisotropy");
    extensionsOf(builder)["KHR_materials_anisotropy"] = {
        {"anisotropyStrength", 0.5},
        {"anisotropyRotation", 1.25},
        {"anisotropyTexture", {{"index", 3}}},
    };
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.anisotropy.has_value());
    EXPECT_EQ(material.anisotropy->anisotropyStrength, 0.5f);
    EXPECT_EQ(material.anisotropy->anisotropyRotation, 1.25f);
    ASSERT_TRUE(material.anisotropy->anisotropyTexture.has_value());
    EXPECT_EQ(material.anisotropy->anisotropyTexture->texture.value, 3u);
    EXPECT_TRUE(material.ignoredExtensions.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(SurfaceExtensionsTest, EmptyObjectsTakeTheSpecifiedDefaults) {
    auto builder = materialBuilder();
    extensionsOf(builder)["KHR_materials_iridescence"] = json::object();
    extensionsOf(builder)["KHR_materials_anisotropy"] = json::object();
    builder.addMaterial({});  // Material 1: neither extension.
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    ASSERT_TRUE(material.iridescence.has_value());
    EXPECT_EQ(material.iridescence->iridescenceFactor, 0.0f);
    EXPECT_FLOAT_EQ(material.iridescence->iridescenceIor, 1.3f);
    EXPECT_EQ(material.iridescence->iridescenceThicknessMinimum, 100.0f);
    EXPECT_EQ(material.iridescence->iridescenceThicknessMaximum, 400.0f);
    EXPECT_FALSE(material.iridescence->iridescenceTexture.has_value());
    EXPECT_FALSE(material.iridescence->iridescenceThicknessTexture.has_value());
    ASSERT_TRUE(material.anisotropy.has_value());
    EXPECT_EQ(material.anisotropy->anisotropyStrength, 0.0f);
    EXPECT_EQ(material.anisotropy->anisotropyRotation, 0.0f);
    EXPECT_FALSE(material.anisotropy->anisotropyTexture.has_value());
    EXPECT_FALSE(scene->materials[1].iridescence.has_value());
    EXPECT_FALSE(scene->materials[1].anisotropy.has_value());
}

// Both are implemented, so a file may require them (IridescenceSuzanne requires iridescence).
TEST(SurfaceExtensionsTest, RequiredIridescenceAndAnisotropyLoad) {
    for (const char* name : {"KHR_materials_iridescence", "KHR_materials_anisotropy"}) {
        SCOPED_TRACE(name);
        auto builder = materialBuilder();
        builder.json()["extensionsUsed"].push_back(name);
        builder.json()["extensionsRequired"].push_back(name);
        extensionsOf(builder)[name] = json::object();
        auto scene = loadGltf(builder, {.strict = true});
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        EXPECT_TRUE(scene->extensionsIgnored.empty());
    }
}

TEST(SurfaceExtensionsTest, TextureIndicesAreChecked) {
    const std::vector<std::pair<std::string, std::string>> slots = {
        {"KHR_materials_iridescence", "iridescenceTexture"},
        {"KHR_materials_iridescence", "iridescenceThicknessTexture"},
        {"KHR_materials_anisotropy", "anisotropyTexture"},
    };
    for (const auto& [extension, slot] : slots) {
        SCOPED_TRACE(extension + " " + slot);
        auto builder = materialBuilder(2);
        extensionsOf(builder)[extension][slot] = {{"index", 7}};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"test.gltf: material 0 " + extension + " " + slot + " refers to texture 7",
                     "the asset has 2 textures"});
    }
}

TEST(SurfaceExtensionsTest, InvalidValuesNameTheMaterialFieldAndValue) {
    struct Case {
        const char* name;
        json extensions;
        std::string fragment;
    };
    const std::vector<Case> cases = {
        {"IridescenceFactorAboveOne",
         {{"KHR_materials_iridescence", {{"iridescenceFactor", 1.5}}}},
         "material 0 KHR_materials_iridescence has an invalid iridescenceFactor (1.5; it must "
         "lie in [0, 1])."},
        {"FilmIorBelowOne",
         {{"KHR_materials_iridescence", {{"iridescenceIor", 0.5}}}},
         "material 0 KHR_materials_iridescence has an invalid iridescenceIor (0.5; it must be at "
         "least 1)."},
        {"NegativeThickness",
         {{"KHR_materials_iridescence", {{"iridescenceThicknessMinimum", -10}}}},
         "material 0 KHR_materials_iridescence has an invalid iridescenceThicknessMinimum (-10; "
         "it must be at least 0)."},
        {"ThicknessNotANumber",
         {{"KHR_materials_iridescence", {{"iridescenceThicknessMaximum", "thick"}}}},
         "'iridescenceThicknessMaximum'"},
        {"NegativeStrength",
         {{"KHR_materials_anisotropy", {{"anisotropyStrength", -0.5}}}},
         "material 0 KHR_materials_anisotropy has an invalid anisotropyStrength (-0.5; it must "
         "lie in [0, 1])."},
        {"RotationNotANumber",
         {{"KHR_materials_anisotropy", {{"anisotropyRotation", {1, 2}}}}},
         "'anisotropyRotation'"},
        {"DirectionTextureWithoutIndex",
         {{"KHR_materials_anisotropy", {{"anisotropyTexture", {{"texCoord", 0}}}}}},
         "material 0 KHR_materials_anisotropy anisotropyTexture"},
        {"ExtensionNotAnObject",
         {{"KHR_materials_iridescence", true}},
         "material 0 has an invalid KHR_materials_iridescence extension"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        auto builder = materialBuilder();
        builder.json()["materials"][0]["extensions"] = c.extensions;
        const auto result = loadGltf(builder);
        ASSERT_FALSE(result.ok());
        EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat);
        EXPECT_NE(result.error().message.find(c.fragment), std::string::npos)
            << "missing '" << c.fragment << "' in: " << result.error().message;
    }
}

}  // namespace
}  // namespace encore::scene
