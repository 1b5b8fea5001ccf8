// KHR_materials_diffuse_transmission on the GPU: a thin, rough white plane facing the camera and
// lit only from behind (a directional light, or an environment that is bright only behind it)
// stays dark without the extension and lets the light through with it, tinted by the colour
// factor and its sRGB texture, scaled by the factor and its texture's alpha, absorbed by a
// volume; the same in every strategy that shades materials, visibility's compute resolve
// included. The expected radiances follow the Khronos Sample Renderer's formulas (a Lambertian
// BTDF about the negated normal, mixed into the diffuse lobe by the factor, under the dielectric
// Fresnel split); docs/shading.md says why no reference picture is compared.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TextureFixtures.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 32;
constexpr float kLightIntensity = 10.0f;  // Lux, of the directional light.
// The light's tilt away from the plane's normal axis (it comes from behind and above).
constexpr float kLightTilt = glm::radians(30.0f);

enum class Lit {
    FromBehind,  // A directional light behind the plane, no image-based light.
    FromFront,   // The same light mirrored to the camera's side.
    Environment  // No light; an environment bright behind the plane, black in front.
};

using Rgba8 = std::array<std::uint8_t, 4>;

struct LeafDesc {
    glm::vec4 baseColor{1.0f};
    std::optional<nlohmann::json> diffuseTransmission;
    std::optional<nlohmann::json> volume;
    std::optional<Rgba8> factorTexture;  // diffuseTransmissionTexture.
    std::optional<Rgba8> colorTexture;   // diffuseTransmissionColorTexture.
};

std::uint32_t addPixelTexture(test::GltfBuilder& builder, Rgba8 rgba) {
    const std::vector<std::uint8_t> png = test::encodePngBytes(test::solidImage(rgba));
    const std::uint32_t image = test::addEmbeddedImage(builder, png, "image/png");
    builder.json()["textures"].push_back({{"source", image}});
    return std::uint32_t(builder.json()["textures"].size() - 1);
}

// A 4x4 fully rough dielectric plane (white unless `leaf` says otherwise) at z = 0 facing the
// camera (+Z), and, unless lit by the environment, a directional light tilted kLightTilt from the Z
// axis.
scene::SceneData leafScene(const LeafDesc& leaf, Lit lit) {
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc plane = builder.addFacingQuad({-2, -2}, {2, 2});
    plane.material = builder.addMaterial({.baseColor = leaf.baseColor, .roughness = 1.0f});
    auto& json = builder.json();
    auto use = [&](const char* name, const nlohmann::json& value) -> nlohmann::json& {
        json["extensionsUsed"].push_back(name);
        return json["materials"][*plane.material]["extensions"][name] = value;
    };
    if (leaf.diffuseTransmission) {
        nlohmann::json& extension =
            use("KHR_materials_diffuse_transmission", *leaf.diffuseTransmission);
        if (leaf.factorTexture) {
            extension["diffuseTransmissionTexture"] = {
                {"index", addPixelTexture(builder, *leaf.factorTexture)}};
        }
        if (leaf.colorTexture) {
            extension["diffuseTransmissionColorTexture"] = {
                {"index", addPixelTexture(builder, *leaf.colorTexture)}};
        }
    }
    if (leaf.volume) {
        use("KHR_materials_volume", *leaf.volume);
    }
    std::vector<std::uint32_t> nodes = {builder.addNode({.mesh = builder.addMesh(plane)})};
    if (lit != Lit::Environment) {
        json["extensionsUsed"].push_back("KHR_lights_punctual");
        json["extensions"]["KHR_lights_punctual"]["lights"] = {
            {{"type", "directional"}, {"intensity", kLightIntensity}}};
        // Lights shine along the node's -Z: turned about X, towards +Z (through the plane from
        // behind) or -Z (onto it from the front), and down by kLightTilt.
        const float angle = lit == Lit::FromBehind ? glm::pi<float>() + kLightTilt : -kLightTilt;
        const std::uint32_t light =
            builder.addNode({.rotation = glm::angleAxis(angle, glm::vec3(1, 0, 0))});
        json["nodes"][light]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
        nodes.push_back(light);
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "leaf.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene.ok() && scene->warnings.empty());
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// White (1, 1, 1) where the direction points behind the plane (z < 0), black in front. The
// panorama's column u looks along (cos 2 pi u, ., sin 2 pi u): its right half is behind.
std::shared_ptr<Environment> backLitEnvironment() {
    static std::shared_ptr<Environment> shared = [] {
        image::HdrImage panorama{64, 32, std::vector<float>(64 * 32 * 3, 0.0f)};
        for (std::uint32_t y = 0; y < panorama.height; ++y) {
            for (std::uint32_t x = panorama.width / 2; x < panorama.width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    panorama.rgb[(std::size_t(y) * panorama.width + x) * 3 + c] = 1.0f;
                }
            }
        }
        gpu::Context* context = test::vulkanContext();
        static shaders::ShaderLibrary shaders(context->device());
        auto created = Environment::create(context->device(), context->queue(), shaders, panorama,
                                           test::testEnvironmentOptions());
        EXPECT_TRUE(created.ok());
        return created.ok() ? std::make_shared<Environment>(std::move(*created)) : nullptr;
    }();
    return shared;
}

RendererOptions leafOptions(Lit lit, bool hdr) {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.target.hdr = hdr;  // Linear colour read back.
    options.lighting.imageBasedLighting = lit == Lit::Environment;
    if (lit == Lit::Environment) {
        options.environment = backLitEnvironment();
    }
    return options;
}

// The linear RGB at the middle of the plane.
glm::vec3 radiance(const LeafDesc& leaf, Lit lit) {
    gpu::Context* context = test::vulkanContext();
    auto renderer = Renderer::create(*context, leafOptions(lit, true));
    EXPECT_TRUE(renderer.ok());
    if (!renderer) {
        return glm::vec3(-1.0f);
    }
    EXPECT_TRUE(renderer->prepare(leafScene(leaf, lit), StrategyKind::Bundles).ok());
    renderer->renderFrame(test::frontCamera());
    auto hdr = renderer->readHdrImage();
    EXPECT_TRUE(hdr.ok());
    EXPECT_TRUE(context->checkNoErrors("diffuse transmission").ok());
    if (!hdr) {
        return glm::vec3(-1.0f);
    }
    const std::size_t at = (std::size_t(kSize / 2) * kSize + kSize / 2) * 4;
    return glm::vec3((*hdr)[at], (*hdr)[at + 1], (*hdr)[at + 2]);
}

nlohmann::json diffuseTransmission(float factor, glm::vec3 color = glm::vec3(1.0f)) {
    return {{"diffuseTransmissionFactor", factor},
            {"diffuseTransmissionColorFactor", {color.r, color.g, color.b}}};
}

// What the light behind the plane gives through it at full factor, for a white tint: the
// Lambertian BTDF (irradiance cos(tilt) * E over pi) less the dielectric Fresnel reflectance
// (Schlick, F0 0.04) at the half vector of the view (+Z) and the light.
float expectedThroughWhite() {
    const glm::vec3 l(0.0f, std::sin(kLightTilt), -std::cos(kLightTilt));
    const float vDotH = glm::normalize(l + glm::vec3(0, 0, 1)).z;
    const float fresnel = 0.04f + 0.96f * std::pow(1.0f - vDotH, 5.0f);
    return kLightIntensity * std::cos(kLightTilt) / glm::pi<float>() * (1.0f - fresnel);
}

TEST(DiffuseTransmissionRenderTest, LightFromBehindPassesThroughTintedByTheColour) {
    ENCORE_REQUIRE_VULKAN(context);
    const glm::vec3 plain = radiance({}, Lit::FromBehind);
    EXPECT_LT(plain.r, 1e-3f) << "without the extension the light behind does not pass";

    const glm::vec3 tint(1.0f, 0.5f, 0.25f);
    const glm::vec3 through =
        radiance({.diffuseTransmission = diffuseTransmission(1, tint)}, Lit::FromBehind);
    EXPECT_NEAR(through.r, expectedThroughWhite(), 0.03f * expectedThroughWhite());
    EXPECT_NEAR(through.g / through.r, 0.5f, 0.01f);
    EXPECT_NEAR(through.b / through.r, 0.25f, 0.01f);

    // The factor mixes the transmitted light with the (here unlit) diffuse reflection.
    const glm::vec3 half =
        radiance({.diffuseTransmission = diffuseTransmission(0.5f, tint)}, Lit::FromBehind);
    EXPECT_NEAR(half.r / through.r, 0.5f, 0.01f);
}

TEST(DiffuseTransmissionRenderTest, LightInFrontIsLostToTheFarSide) {
    ENCORE_REQUIRE_VULKAN(context);
    // A fully transmissive diffuse layer sends light from the front away behind it: what is left
    // on the camera's side is the specular reflection alone.
    const glm::vec3 plain = radiance({}, Lit::FromFront);
    const glm::vec3 leaf =
        radiance({.diffuseTransmission = diffuseTransmission(1)}, Lit::FromFront);
    EXPECT_GT(plain.r, 1.5f);
    EXPECT_LT(leaf.r, 0.2f * plain.r) << "plain " << plain.r << ", leaf " << leaf.r;
    EXPECT_GT(leaf.r, 0.0f);  // The specular lobe stays.
}

TEST(DiffuseTransmissionRenderTest, EnvironmentBehindShinesThrough) {
    ENCORE_REQUIRE_VULKAN(context);
    // The front hemisphere is black; a black base colour reflects nothing diffusely, so without
    // the extension only the rough specular lobe's tail below the horizon reaches the camera.
    // With it, the irradiance about the negated normal, tinted, under the same specular.
    const glm::vec4 black(0.0f, 0.0f, 0.0f, 1.0f);
    const glm::vec3 plain = radiance({.baseColor = black}, Lit::Environment);
    const glm::vec3 tint(0.25f, 0.5f, 1.0f);
    const glm::vec3 leaf =
        radiance({.baseColor = black, .diffuseTransmission = diffuseTransmission(1, tint)},
                 Lit::Environment);
    const glm::vec3 through = leaf - plain;
    EXPECT_LT(plain.b, 0.25f);
    EXPECT_GT(through.b, 0.6f) << "plain " << plain.b << ", leaf " << leaf.b;
    EXPECT_NEAR(through.r / through.b, 0.25f, 0.01f);
    EXPECT_NEAR(through.g / through.b, 0.5f, 0.01f);
    // A white plane without the extension shows the front's (black) irradiance, not the back's.
    EXPECT_LT(radiance({}, Lit::Environment).b, 0.5f * leaf.b);
}

TEST(DiffuseTransmissionRenderTest, TexturesScaleTheFactorAndTheColour) {
    ENCORE_REQUIRE_VULKAN(context);
    const glm::vec3 full =
        radiance({.diffuseTransmission = diffuseTransmission(1)}, Lit::FromBehind);
    // The factor reads the alpha channel (linear): 0 blocks, 128 passes about half.
    const glm::vec3 blocked = radiance(
        {.diffuseTransmission = diffuseTransmission(1), .factorTexture = Rgba8{255, 255, 255, 0}},
        Lit::FromBehind);
    EXPECT_LT(blocked.r, 1e-3f);
    const glm::vec3 half = radiance(
        {.diffuseTransmission = diffuseTransmission(1), .factorTexture = Rgba8{0, 0, 0, 128}},
        Lit::FromBehind);
    EXPECT_NEAR(half.r / full.r, 128.0f / 255.0f, 0.01f);
    // The colour texture is sRGB: 128 decodes to 0.216, and multiplies the factor.
    const glm::vec3 tinted = radiance({.diffuseTransmission = diffuseTransmission(1, {1, 1, 0.5f}),
                                       .colorTexture = Rgba8{255, 128, 255, 255}},
                                      Lit::FromBehind);
    EXPECT_NEAR(tinted.r / full.r, 1.0f, 0.01f);
    EXPECT_NEAR(tinted.g / full.r, 0.2158f, 0.01f);
    EXPECT_NEAR(tinted.b / full.r, 0.5f, 0.01f);
}

TEST(DiffuseTransmissionRenderTest, VolumeAbsorbsOverItsThickness) {
    ENCORE_REQUIRE_VULKAN(context);
    const glm::vec3 thin =
        radiance({.diffuseTransmission = diffuseTransmission(1)}, Lit::FromBehind);
    // One unit thick, white turns attenuationColor after one unit: the colour exactly.
    const glm::vec3 thick = radiance({.diffuseTransmission = diffuseTransmission(1),
                                      .volume = nlohmann::json{{"thicknessFactor", 1.0},
                                                               {"attenuationDistance", 1.0},
                                                               {"attenuationColor", {0.5, 1, 1}}}},
                                     Lit::FromBehind);
    EXPECT_NEAR(thick.r / thin.r, 0.5f, 0.01f);
    EXPECT_NEAR(thick.g / thin.g, 1.0f, 0.01f);
}

TEST(DiffuseTransmissionRenderTest, EveryMaterialStrategyShadesItAlike) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene =
        leafScene({.diffuseTransmission = diffuseTransmission(0.75f, {1.0f, 0.5f, 0.25f}),
                   .colorTexture = Rgba8{255, 200, 255, 255}},
                  Lit::FromBehind);
    std::optional<image::ImageRgba8> expected;
    for (const StrategyChoice& choice : test::everyStrategyChoice()) {
        if (!test::shadesMaterials(choice.kind)) {
            continue;  // Their frames shade no materials at all.
        }
        SCOPED_TRACE(std::string(strategyName(choice.kind)) + (choice.bundle ? "+bundle" : ""));
        auto renderer = Renderer::create(*context, leafOptions(Lit::FromBehind, false));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, choice.kind, choice.bundle).ok());
        renderer->renderFrame(test::frontCamera());
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        EXPECT_TRUE(context->checkNoErrors("diffuse transmission").ok());
        const test::Rgba middle = test::pixelAt(*image, kSize / 2, kSize / 2);
        EXPECT_GT(middle[0], 100) << test::describe(middle);  // Lit through.
        if (!expected) {
            expected = std::move(*image);
            continue;
        }
        EXPECT_EQ(test::differingPixels(*expected, *image, 2), 0u);
    }
}

}  // namespace
}  // namespace encore::render
