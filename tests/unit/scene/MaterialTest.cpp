// Materials, textures, samplers and images, including the missing-image warnings.

#include <gtest/gtest.h>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "core/FileIO.h"
#include "core/Log.h"
#include "encore/image/ImageCodec.h"
#include "scene/SceneGenerator.h"

namespace encore::scene {
namespace {

using testing::loadGltf;
using testing::triangleBuilder;

TEST(MaterialTest, DefaultMaterialIsAppendedOnce) {
    auto builder = triangleBuilder();
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    builder.addMesh({.attributes = {{"POSITION", positions}}});
    builder.addMaterial({.baseColor = {1, 0, 0, 1}});
    builder.json()["meshes"][1]["primitives"].push_back(
        {{"attributes", {{"POSITION", positions}}}, {"material", 0}});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->materials.size(), 2u);
    EXPECT_FALSE(scene->materials[0].isDefault);
    EXPECT_TRUE(scene->materials[1].isDefault);
    EXPECT_EQ(scene->meshes[0].primitives[0].material.value, 1u);
    EXPECT_EQ(scene->meshes[1].primitives[0].material.value, 1u);
    EXPECT_EQ(scene->meshes[1].primitives[1].material.value, 0u);
    const Material& fallback = scene->materials[1];
    EXPECT_EQ(fallback.baseColorFactor, glm::vec4(1.0f));
    EXPECT_EQ(fallback.metallicFactor, 1.0f);
    EXPECT_EQ(fallback.roughnessFactor, 1.0f);
    EXPECT_EQ(fallback.alphaMode, AlphaMode::Opaque);
}

TEST(MaterialTest, FactorsAlphaAndSidedness) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["material"] =
        builder.addMaterial({.baseColor = {0.5f, 0.25f, 1, 0.5f},
                             .metallic = 0.25f,
                             .roughness = 0.75f,
                             .alphaMode = "MASK",
                             .alphaCutoff = 0.0f,
                             .doubleSided = true});
    builder.addMaterial({.alphaMode = "BLEND"});
    builder.json()["materials"][0]["emissiveFactor"] = {1, 0.5, 0};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Material& material = scene->materials[0];
    EXPECT_EQ(material.baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 0.5f));
    EXPECT_EQ(material.metallicFactor, 0.25f);
    EXPECT_EQ(material.roughnessFactor, 0.75f);
    EXPECT_EQ(material.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(material.alphaCutoff, 0.0f);  // An explicit 0 stays 0.
    EXPECT_TRUE(material.doubleSided);
    EXPECT_EQ(material.emissiveFactor, glm::vec3(1, 0.5f, 0));
    EXPECT_EQ(scene->materials[1].alphaMode, AlphaMode::Blend);
    EXPECT_EQ(scene->materials[1].alphaCutoff, 0.5f);
}

TEST(MaterialTest, UnknownAlphaModeIsAnError) {
    auto builder = triangleBuilder();
    builder.addMaterial({.alphaMode = "GLASS"});
    testing::expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"material 0", "GLASS"});
}

TEST(MaterialTest, SamplerMapping) {
    auto builder = triangleBuilder();
    builder.addSampler(9728, 9728, 33071, 33648);  // Nearest, no mipmaps, clamp / mirror.
    builder.addSampler(9729, 9984);                // Nearest mipmap nearest.
    builder.addSampler(std::nullopt, 9987);        // Linear mipmap linear.
    builder.addSampler(std::nullopt, 9985);        // Linear mipmap nearest.
    builder.addSampler(std::nullopt, std::nullopt);
    auto scene = loadGltf(builder, {.decodeImages = false});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->samplers.size(), 5u);
    const auto& s = scene->samplers;
    EXPECT_EQ(s[0].magFilter, Filter::Nearest);
    EXPECT_EQ(s[0].minFilter, Filter::Nearest);
    EXPECT_FALSE(s[0].useMipmaps);
    EXPECT_EQ(s[0].wrapS, Wrap::ClampToEdge);
    EXPECT_EQ(s[0].wrapT, Wrap::MirroredRepeat);
    EXPECT_EQ(s[1].minFilter, Filter::Nearest);
    EXPECT_EQ(s[1].mipmapFilter, Filter::Nearest);
    EXPECT_TRUE(s[1].useMipmaps);
    EXPECT_EQ(s[2].minFilter, Filter::Linear);
    EXPECT_EQ(s[2].mipmapFilter, Filter::Linear);
    EXPECT_EQ(s[3].minFilter, Filter::Linear);
    EXPECT_EQ(s[3].mipmapFilter, Filter::Nearest);
    EXPECT_EQ(s[4].magFilter, Filter::Linear);
    EXPECT_TRUE(s[4].useMipmaps);
    EXPECT_EQ(s[4].wrapS, Wrap::Repeat);
}

TEST(MaterialTest, InvalidSamplerEnum) {
    auto builder = triangleBuilder();
    builder.addSampler(1234, std::nullopt);
    testing::expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"sampler 0", "1234"});
}

TEST(MaterialTest, TexturesGetADefaultSamplerAndTransforms) {
    auto builder = triangleBuilder();
    const auto texture = builder.addTexture("a.png");
    builder.addMaterial({.baseColorTexture = texture});
    builder.json()["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
        {"index", texture},
        {"texCoord", 1},
        {"extensions",
         {{"KHR_texture_transform",
           {{"offset", {0.5, 0.25}}, {"rotation", 1.5}, {"scale", {2, 3}}}}}}};
    auto scene = loadGltf(builder, {.decodeImages = false});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->textures.size(), 1u);
    ASSERT_EQ(scene->samplers.size(), 1u);
    EXPECT_EQ(scene->textures[0].sampler.value, 0u);
    EXPECT_EQ(scene->textures[0].image.value, 0u);
    const auto& ref = scene->materials[0].baseColorTexture;
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->texCoord, 1u);
    ASSERT_TRUE(ref->transform);
    EXPECT_EQ(ref->transform->offset, glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(ref->transform->rotation, 1.5f);
    EXPECT_EQ(ref->transform->scale, glm::vec2(2, 3));
}

TEST(MaterialTest, MissingImageIsAWarning) {
    std::vector<std::string> logged;
    const auto previous = setLogSink([&](LogLevel level, std::string_view message) {
        if (level == LogLevel::Warning) {
            logged.emplace_back(message);
        }
    });
    for (bool decode : {true, false}) {
        logged.clear();
        auto builder = triangleBuilder();
        builder.addTexture("textures/missing.png");
        auto scene = loadGltf(builder, {.decodeImages = decode});
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_EQ(scene->warnings.size(), 1u);
        const std::string& warning = scene->warnings[0];
        EXPECT_EQ(warning.rfind("test.gltf: image 0 ('textures/missing.png') cannot be read (", 0),
                  0u)
            << warning;
        EXPECT_NE(warning.find("missing.png' does not exist."), std::string::npos) << warning;
        EXPECT_NE(warning.find("drawing it with a default texture."), std::string::npos);
        EXPECT_EQ(logged, scene->warnings);
        EXPECT_TRUE(scene->images[0].rgba8.empty());
        EXPECT_EQ(scene->images[0].name, "textures/missing.png");
    }
    setLogSink(previous);
}

TEST(MaterialTest, ImagesDecodeFromFilesAndBufferViews) {
    image::ImageRgba8 pixels{2, 1, {255, 0, 0, 255, 0, 255, 0, 255}};
    auto png = image::encodePng(pixels);
    ASSERT_TRUE(png.ok()) << png.error().message;
    const auto dir = test::makeTempDir("scene-images");
    ASSERT_TRUE(writeFile(dir / "red green.png", *png).ok());

    auto builder = triangleBuilder();
    builder.addTexture("red%20green.png");
    const auto view = builder.addBufferView(*png);
    builder.json()["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
    builder.json()["images"].push_back({{"uri", "data:image/png;base64,bm90IGEgcG5n"}});
    auto scene = loadGltf(builder, {}, dir);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->images.size(), 3u);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(scene->images[i].width, 2u);
        EXPECT_EQ(scene->images[i].height, 1u);
        EXPECT_EQ(scene->images[i].rgba8, pixels.pixels);
    }
    EXPECT_EQ(scene->images[1].name, "image 1");
    // "not a png" cannot be decoded: a warning, not an error.
    ASSERT_EQ(scene->warnings.size(), 1u);
    EXPECT_NE(scene->warnings[0].find("image 2"), std::string::npos);
}

TEST(MaterialTest, GeneratedMaterialsVaryMetalAndRoughness) {
    GeneratorOptions options;
    options.objectCount = 8;
    options.materialCount = 8;
    auto glb = generateSceneGlb(options);
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto scene = loadSceneFromMemory(*glb, {}, "generated.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->materials.size(), 8u);
    int metals = 0;
    for (std::size_t i = 0; i < scene->materials.size(); ++i) {
        const Material& material = scene->materials[i];
        EXPECT_TRUE(material.metallicFactor == 0.0f || material.metallicFactor == 1.0f);
        metals += material.metallicFactor == 1.0f;
        EXPECT_GE(material.roughnessFactor, 0.2f - 1e-6f);
        EXPECT_LE(material.roughnessFactor, 0.9f + 1e-6f);
        for (std::size_t j = 0; j < i; ++j) {
            EXPECT_NE(material.baseColorFactor, scene->materials[j].baseColorFactor)
                << "materials " << j << " and " << i;
            EXPECT_NE(material.roughnessFactor, scene->materials[j].roughnessFactor);
        }
    }
    EXPECT_FLOAT_EQ(scene->materials.front().roughnessFactor, 0.2f);
    EXPECT_FLOAT_EQ(scene->materials.back().roughnessFactor, 0.9f);
    EXPECT_GE(metals, 2);
    EXPECT_LT(metals, 8);
}

TEST(MaterialTest, GeneratedTexturesGoToEveryOtherMaterial) {
    GeneratorOptions options;
    options.objectCount = 8;
    options.materialCount = 5;
    options.textures = true;
    auto glb = generateSceneGlb(options);
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto scene = loadSceneFromMemory(*glb, {}, "generated.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->images.size(), 2u);
    for (const Image& image : scene->images) {
        EXPECT_EQ(image.width, 64u);
        EXPECT_EQ(image.height, 64u);
        ASSERT_EQ(image.rgba8.size(), 64u * 64u * 4u);
    }
    // The checker is light and darker grey; the metallic-roughness map has metal (blue 255)
    // and dielectric (blue 0) bands and a roughness ramp in green.
    const auto& checker = scene->images[0].rgba8;
    EXPECT_EQ(checker[0], 255);
    EXPECT_EQ(checker[8 * 4], 150);
    const auto& metallicRoughness = scene->images[1].rgba8;
    EXPECT_EQ(metallicRoughness[2], 255);
    EXPECT_EQ(metallicRoughness[16 * 4 + 2], 0);
    EXPECT_LT(metallicRoughness[1], metallicRoughness[63 * 64 * 4 + 1]);
    ASSERT_EQ(scene->materials.size(), 5u);
    for (std::size_t i = 0; i < scene->materials.size(); ++i) {
        const Material& material = scene->materials[i];
        EXPECT_EQ(material.baseColorTexture.has_value(), i % 2 == 1) << "material " << i;
        EXPECT_EQ(material.metallicRoughnessTexture.has_value(), i % 2 == 1) << "material " << i;
        if (material.baseColorTexture) {
            EXPECT_EQ(scene->textures[material.baseColorTexture->texture.index()].image.index(),
                      0u);
            EXPECT_EQ(
                scene->textures[material.metallicRoughnessTexture->texture.index()].image.index(),
                1u);
            EXPECT_EQ(material.metallicFactor, 1.0f);
        }
    }

    options.textures = false;
    auto plain = generateSceneGlb(options);
    ASSERT_TRUE(plain.ok());
    auto untextured = loadSceneFromMemory(*plain, {}, "plain.glb");
    ASSERT_TRUE(untextured.ok());
    EXPECT_TRUE(untextured->images.empty());
    for (const Material& material : untextured->materials) {
        EXPECT_FALSE(material.baseColorTexture);
    }
}

}  // namespace
}  // namespace encore::scene
