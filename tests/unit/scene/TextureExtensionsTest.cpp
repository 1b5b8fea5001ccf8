// Texture extensions in the loader: EXT_texture_webp's image preferred to the core source (the
// fallback left undecoded), the fallback drawn when an optional WebP image fails, an error when
// a required one does; KHR_texture_basisu's KTX2 images never decoded, refused when required
// with the images named.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TextureFixtures.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::expectError;
using testing::loadGlb;

constexpr std::array<std::uint8_t, 4> kWebpColor = {20, 200, 90, 128};
constexpr std::array<std::uint8_t, 4> kPngColor = {250, 10, 10, 255};

// A triangle whose material's base colour texture 0 has a PNG source (image 0) and, unless
// `webp` is empty, an EXT_texture_webp image (image 1) holding those bytes.
test::GltfBuilder webpBuilder(const std::vector<std::uint8_t>& webp, bool withFallback = true) {
    auto builder = testing::triangleBuilder();
    auto& root = builder.json();
    const std::uint32_t png = test::addEmbeddedImage(
        builder, test::encodePngBytes(test::solidImage(kPngColor, 2, 2)), "image/png");
    json texture = json::object();
    if (withFallback) {
        texture["source"] = png;
    }
    if (!webp.empty()) {
        const std::uint32_t image = test::addEmbeddedImage(builder, webp, "image/webp");
        texture["extensions"]["EXT_texture_webp"] = {{"source", image}};
        root["extensionsUsed"].push_back("EXT_texture_webp");
    }
    root["textures"].push_back(texture);
    root["meshes"][0]["primitives"][0]["material"] = builder.addMaterial({.baseColorTexture = 0});
    return builder;
}

std::vector<std::uint8_t> greenWebp(bool lossless = true) {
    return test::encodeWebpBytes(test::solidImage(kWebpColor, 4, 2), lossless);
}

void expectSolid(const Image& image, std::array<std::uint8_t, 4> rgba, int tolerance = 0) {
    ASSERT_FALSE(image.rgba8.empty()) << image.name << " was not decoded";
    for (std::size_t i = 0; i < image.rgba8.size(); ++i) {
        ASSERT_LE(std::abs(int(image.rgba8[i]) - int(rgba[i % 4])), tolerance)
            << image.name << ", byte " << i;
    }
}

TEST(TextureExtensionsTest, TheWebpImageIsDrawnAndTheFallbackLeftUndecoded) {
    auto scene = loadGlb(webpBuilder(greenWebp()));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty());
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    ASSERT_EQ(scene->textures.size(), 1u);
    EXPECT_EQ(scene->textures[0].image.value, 1u);
    EXPECT_EQ(scene->images[1].width, 4u);
    EXPECT_EQ(scene->images[1].height, 2u);
    expectSolid(scene->images[1], kWebpColor);    // Lossless: exact, alpha included.
    EXPECT_TRUE(scene->images[0].rgba8.empty());  // No texture draws the PNG.
}

TEST(TextureExtensionsTest, LossyWebpDecodesCloseToItsSource) {
    auto scene = loadGlb(webpBuilder(greenWebp(/*lossless=*/false)));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->textures[0].image.value, 1u);
    expectSolid(scene->images[1], kWebpColor, 6);
}

TEST(TextureExtensionsTest, ARequiredWebpImageNeedsNoFallback) {
    auto builder = webpBuilder(greenWebp(), /*withFallback=*/false);
    builder.json()["extensionsRequired"] = {"EXT_texture_webp"};
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->textures[0].image.value, 1u);
    expectSolid(scene->images[1], kWebpColor);
    EXPECT_FALSE(scene->images[0].rgba8.empty());  // Referenced by no texture: decoded as before.
}

TEST(TextureExtensionsTest, AnOptionalWebpImageThatFailsFallsBackWithAWarning) {
    auto webp = greenWebp();
    webp.resize(webp.size() / 2);  // Cut short.
    auto scene = loadGlb(webpBuilder(webp));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->textures[0].image.value, 0u);
    expectSolid(scene->images[0], kPngColor);
    ASSERT_EQ(scene->warnings.size(), 1u);
    const std::string& warning = scene->warnings[0];
    for (const char* fragment : {"test.glb: texture 0's EXT_texture_webp image 1", "cannot be read",
                                 "drawing its fallback source, image 0."}) {
        EXPECT_NE(warning.find(fragment), std::string::npos) << warning;
    }
    // Strict: the warning is an error.
    LoadOptions strict;
    strict.strict = true;
    expectError(loadGlb(webpBuilder(webp), strict), ErrorCode::InvalidFormat,
                {"texture 0's EXT_texture_webp image 1"});
    // Without a fallback a default texture stands in.
    auto bare = loadGlb(webpBuilder(webp, /*withFallback=*/false));
    ASSERT_TRUE(bare.ok()) << bare.error().message;
    EXPECT_FALSE(bare->textures[0].image.valid());
    ASSERT_FALSE(bare->warnings.empty());
    EXPECT_NE(bare->warnings[0].find("it has no fallback source"), std::string::npos);
}

TEST(TextureExtensionsTest, ARequiredWebpImageThatFailsIsAnError) {
    auto webp = greenWebp();
    webp[12] ^= 0xFF;  // The first chunk's name: no longer VP8L.
    auto builder = webpBuilder(webp);
    builder.json()["extensionsRequired"] = {"EXT_texture_webp"};
    expectError(loadGlb(builder), ErrorCode::InvalidFormat,
                {"test.glb: texture 0's EXT_texture_webp image 1", "WebP",
                 "the asset requires EXT_texture_webp, so no fallback image stands in for it."});
}

TEST(TextureExtensionsTest, WithoutDecodingTheWebpImageIsChosenAllTheSame) {
    LoadOptions options;
    options.decodeImages = false;
    auto scene = loadGlb(webpBuilder(greenWebp()), options);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->textures[0].image.value, 1u);
    EXPECT_TRUE(scene->images[1].rgba8.empty());
}

TEST(TextureExtensionsTest, AnImageNamedOnlyByTheWebpExtensionIsCheckedThere) {
    auto builder = webpBuilder(greenWebp());
    builder.json()["textures"][0]["extensions"]["EXT_texture_webp"]["source"] = 5;
    expectError(loadGlb(builder), ErrorCode::InvalidFormat,
                {"texture 0 EXT_texture_webp refers to image 5, but the asset has 2 images."});
}

// A texture whose KHR_texture_basisu image (1, 'wood.ktx2', never read) has a PNG fallback.
test::GltfBuilder basisuBuilder(bool required) {
    auto builder = webpBuilder({});
    auto& root = builder.json();
    root["images"].push_back({{"uri", "wood.ktx2"}});
    root["textures"][0]["extensions"]["KHR_texture_basisu"] = {{"source", 1}};
    root["extensionsUsed"] = {"KHR_texture_basisu"};
    if (required) {
        root["extensionsRequired"] = {"KHR_texture_basisu"};
    }
    return builder;
}

TEST(TextureExtensionsTest, ARequiredBasisuTextureIsRefusedNamingItsImages) {
    expectError(loadGlb(basisuBuilder(true)), ErrorCode::Unsupported,
                {"The asset requires the extension KHR_texture_basisu, which Encore does not "
                 "support (Basis Universal textures need a transcoder, which no Debian package "
                 "provides); its KTX2 images need it: image 1 ('wood.ktx2')."});
}

TEST(TextureExtensionsTest, AnOptionalBasisuTextureDrawsItsFallback) {
    auto scene = loadGlb(basisuBuilder(false));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->textures.size(), 1u);
    EXPECT_EQ(scene->textures[0].image.value, 0u);
    ASSERT_TRUE(scene->textures[0].basisuImage.has_value());
    EXPECT_EQ(scene->textures[0].basisuImage->value, 1u);
    expectSolid(scene->images[0], kPngColor);
    EXPECT_TRUE(scene->images[1].rgba8.empty());
    // One warning, for the extension; none for the KTX2 file that was never read.
    ASSERT_EQ(scene->warnings.size(), 1u) << scene->warnings[0];
    EXPECT_NE(scene->warnings[0].find("KHR_texture_basisu, which Encore does not implement"),
              std::string::npos);
}

}  // namespace
}  // namespace encore::scene
