// Physical checks of the physically based shading on in-code scenes: the white furnace (a
// uniform white environment: white dielectrics and white metals of any roughness reflect exactly
// what arrives, never more), energy that does not grow with roughness, normal-map handedness
// (TANGENT or derived frames, mirrored UVs, mirrored instances) and unlit materials that output
// their base colour exactly.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

// A UV sphere of radius 1 at the origin, facing outward.
std::uint32_t addSphere(test::GltfBuilder& builder, std::uint32_t material) {
    constexpr int kRings = 32;
    constexpr int kSegments = 48;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> texcoords;
    for (int ring = 0; ring <= kRings; ++ring) {
        const float theta = glm::pi<float>() * float(ring) / kRings;
        for (int segment = 0; segment <= kSegments; ++segment) {
            const float phi = glm::two_pi<float>() * float(segment) / kSegments;
            positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                 -std::sin(theta) * std::sin(phi)});
            texcoords.push_back({float(segment) / kSegments, float(ring) / kRings});
        }
    }
    std::vector<std::uint16_t> indices;
    for (int ring = 0; ring < kRings; ++ring) {
        for (int segment = 0; segment < kSegments; ++segment) {
            const std::uint16_t a = std::uint16_t(ring * (kSegments + 1) + segment);
            const std::uint16_t b = std::uint16_t(a + kSegments + 1);
            indices.insert(indices.end(), {a, b, std::uint16_t(a + 1), std::uint16_t(a + 1), b,
                                           std::uint16_t(b + 1)});
        }
    }
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions(positions);
    primitive.attributes["NORMAL"] = builder.addNormals(positions);
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords(texcoords);
    primitive.indices = builder.addIndices(indices);
    primitive.material = material;
    return builder.addNode({.mesh = builder.addMesh(primitive)});
}

// The uniform white environment, built once.
std::shared_ptr<Environment> furnaceEnvironment() {
    static std::shared_ptr<Environment> environment = [] {
        gpu::Context* context = test::vulkanContext();
        if (!context) {
            return std::shared_ptr<Environment>();
        }
        static shaders::ShaderLibrary shaders(context->device());
        auto created = Environment::create(context->device(), context->queue(), shaders,
                                           image::makeUniformEnvironment(1.0f, 1.0f, 1.0f),
                                           test::testEnvironmentOptions());
        return created ? std::make_shared<Environment>(std::move(*created))
                       : std::shared_ptr<Environment>();
    }();
    return environment;
}

struct HdrFrame {
    std::vector<float> rgba;
    // Channel c of pixel (x, y).
    float at(std::uint32_t x, std::uint32_t y, int c) const {
        return rgba[(std::size_t(y) * kSize + x) * 4 + c];
    }
};

// Renders a sphere of one material under `environment` and reads the HDR frame back;
// `editMaterial` may change the material's JSON (extensions) before loading.
HdrFrame renderSphere(
    const test::GltfBuilder::MaterialDesc& desc,
    std::shared_ptr<Environment> environment,
    const std::function<void(test::GltfBuilder&, nlohmann::json&)>& editMaterial = {}) {
    gpu::Context* context = test::vulkanContext();
    test::GltfBuilder builder;
    const std::uint32_t material = builder.addMaterial(desc);
    if (editMaterial) {
        editMaterial(builder, builder.json()["materials"][material]);
    }
    builder.addScene({addSphere(builder, material)});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "sphere.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.target.hdr = true;  // Reads the linear colour back.
    options.environment = std::move(environment);
    auto renderer = Renderer::create(*context, options);
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(*scene, StrategyKind::Bundles).ok());
    renderer->renderFrame(Camera::lookAt({0, 0, 4}, {0, 0, 0}, 0.6f, 1.0f, 0.1f, 10.0f));
    auto hdr = renderer->readHdrImage();
    EXPECT_TRUE(hdr.ok());
    EXPECT_TRUE(context->checkNoErrors("rendering a sphere").ok());
    return {hdr.ok() ? std::move(*hdr) : std::vector<float>(std::size_t(kSize) * kSize * 4)};
}

// Statistics over the pixels fully covered by the sphere (alpha 1).
struct SphereStatistics {
    float minimum = 1e9f;
    float maximum = 0.0f;
    double mean = 0.0;
    std::size_t pixels = 0;
};

SphereStatistics sphereStatistics(const HdrFrame& frame) {
    SphereStatistics stats;
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            if (frame.at(x, y, 3) < 0.999f) {
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                stats.minimum = std::min(stats.minimum, frame.at(x, y, c));
                stats.maximum = std::max(stats.maximum, frame.at(x, y, c));
                stats.mean += frame.at(x, y, c);
            }
            ++stats.pixels;
        }
    }
    stats.mean /= double(std::max<std::size_t>(stats.pixels, 1) * 3);
    return stats;
}

class WhiteFurnaceTest : public ::testing::TestWithParam<float> {};

TEST_P(WhiteFurnaceTest, WhiteDielectricReflectsExactlyWhatArrives) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto stats = sphereStatistics(
        renderSphere({.baseColor = glm::vec4(1.0f), .metallic = 0.0f, .roughness = GetParam()},
                     furnaceEnvironment()));
    ASSERT_GT(stats.pixels, 500u);
    EXPECT_GT(stats.minimum, 0.97f) << "roughness " << GetParam();
    EXPECT_LT(stats.maximum, 1.02f) << "roughness " << GetParam();
}

TEST_P(WhiteFurnaceTest, WhiteMetalReflectsExactlyWhatArrives) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto stats = sphereStatistics(
        renderSphere({.baseColor = glm::vec4(1.0f), .metallic = 1.0f, .roughness = GetParam()},
                     furnaceEnvironment()));
    ASSERT_GT(stats.pixels, 500u);
    // Multiple-scattering compensation keeps rough metals white; the LUT's 16-bit values and
    // its resolution leave a few percent at grazing angles.
    EXPECT_GT(stats.mean, 0.97) << "roughness " << GetParam();
    EXPECT_GT(stats.minimum, 0.9f) << "roughness " << GetParam();
    EXPECT_LT(stats.maximum, 1.03f) << "roughness " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Roughness,
                         WhiteFurnaceTest,
                         ::testing::Values(0.0f, 0.25f, 0.5f, 0.75f, 1.0f));

TEST(ShadingEnergyTest, ReflectedEnergyDoesNotGrowWithRoughness) {
    ENCORE_REQUIRE_VULKAN(context);
    // A grey metal and a coloured dielectric in the furnace: rougher may lose a little energy
    // (single scattering) but must never gain any.
    for (const auto& [baseColor, metallic] : {std::pair{glm::vec4(0.6f, 0.6f, 0.6f, 1.0f), 1.0f},
                                              std::pair{glm::vec4(0.8f, 0.3f, 0.2f, 1.0f), 0.0f}}) {
        double previous = 1e9;
        for (float roughness : {0.05f, 0.25f, 0.5f, 0.75f, 1.0f}) {
            const auto stats = sphereStatistics(
                renderSphere({.baseColor = baseColor, .metallic = metallic, .roughness = roughness},
                             furnaceEnvironment()));
            EXPECT_LE(stats.mean, previous * 1.01)
                << "metallic " << metallic << ", roughness " << roughness;
            EXPECT_LE(stats.maximum, 1.02f);
            previous = stats.mean;
        }
    }
}

// KHR_materials_pbrSpecularGlossiness: a file that requires it renders, and a specular-glossiness
// material with specular 0.04 and diffuse d / 0.96 is the metallic-roughness dielectric of base
// colour d and roughness 1 - glossiness (the extension's own conversion).
TEST(SpecularGlossinessTest, MatchesTheEquivalentMetallicRoughnessMaterial) {
    ENCORE_REQUIRE_VULKAN(context);
    const glm::vec4 base(0.6f, 0.3f, 0.2f, 1.0f);
    const float glossiness = 0.6f;
    const HdrFrame metalRough =
        renderSphere({.baseColor = base, .metallic = 0.0f, .roughness = 1.0f - glossiness},
                     test::testEnvironment());
    const HdrFrame specularGlossy = renderSphere(
        {.baseColor = glm::vec4(1.0f)}, test::testEnvironment(),
        [&](test::GltfBuilder& builder, nlohmann::json& material) {
            const glm::vec3 diffuse = glm::vec3(base) / 0.96f;
            material["extensions"]["KHR_materials_pbrSpecularGlossiness"] = {
                {"diffuseFactor", {diffuse.r, diffuse.g, diffuse.b, 1.0}},
                {"specularFactor", {0.04, 0.04, 0.04}},
                {"glossinessFactor", glossiness}};
            builder.json()["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness"};
            builder.json()["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
        });
    const auto a = sphereStatistics(metalRough);
    const auto b = sphereStatistics(specularGlossy);
    ASSERT_GT(a.pixels, 500u);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_NEAR(b.mean, a.mean, 0.01 * a.mean);
    double largest = 0.0;
    for (std::size_t i = 0; i < metalRough.rgba.size(); ++i) {
        largest = std::max(largest, double(std::abs(metalRough.rgba[i] - specularGlossy.rgba[i])));
    }
    EXPECT_LT(largest, 0.02);
}

// KHR_materials_emissive_strength scales the emission: an emissive black sphere in a black
// world shows exactly emissiveFactor x strength.
TEST(EmissiveTest, EmissiveStrengthScalesTheEmission) {
    ENCORE_REQUIRE_VULKAN(context);
    static std::shared_ptr<Environment> black = [] {
        gpu::Context* gpu = test::vulkanContext();
        static shaders::ShaderLibrary shaders(gpu->device());
        auto created = Environment::create(gpu->device(), gpu->queue(), shaders,
                                           image::makeUniformEnvironment(0.0f, 0.0f, 0.0f),
                                           test::testEnvironmentOptions());
        return std::make_shared<Environment>(std::move(*created));
    }();
    const HdrFrame frame = renderSphere(
        {.baseColor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)}, black,
        [](test::GltfBuilder& builder, nlohmann::json& material) {
            material["emissiveFactor"] = {0.5, 0.25, 1.0};
            material["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 4.0}};
            builder.json()["extensionsUsed"] = {"KHR_materials_emissive_strength"};
        });
    const std::uint32_t centre = kSize / 2;
    EXPECT_NEAR(frame.at(centre, centre, 0), 2.0f, 0.01f);
    EXPECT_NEAR(frame.at(centre, centre, 1), 1.0f, 0.01f);
    EXPECT_NEAR(frame.at(centre, centre, 2), 4.0f, 0.02f);
}

// --- Normal-map handedness -------------------------------------------------------------------

// A 1x1 linear PNG normal map whose tangent-space normal tilts towards +U and +V-up
// (glTF: green points up the image, that is, towards decreasing v).
std::uint32_t addTiltedNormalMap(test::GltfBuilder& builder) {
    const glm::vec3 tilted = glm::normalize(glm::vec3(0.5f, 0.5f, 0.707f));
    const auto encode = [](float v) { return std::uint8_t(std::lround((v * 0.5f + 0.5f) * 255)); };
    image::ImageRgba8 pixel{1, 1, {encode(tilted.x), encode(tilted.y), encode(tilted.z), 255}};
    const auto png = image::encodePng(pixel);
    const std::uint32_t view = builder.addBufferView(*png);
    auto& json = builder.json();
    json["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
    json["textures"].push_back({{"source", json["images"].size() - 1}});
    return static_cast<std::uint32_t>(json["textures"].size() - 1);
}

struct HandednessCase {
    const char* name;
    bool mirrorU;         // u grows towards -X.
    bool mirrorV;         // v grows upwards (+Y) instead of downwards.
    bool mirrorInstance;  // The node scales X by -1.
    bool withTangents;
    float expectedX;  // Sign of the world normal's x and y tilt.
    float expectedY;
};

class NormalMapHandednessTest : public ::testing::TestWithParam<HandednessCase> {};

TEST_P(NormalMapHandednessTest, TiltFollowsTheTextureDirections) {
    const HandednessCase& c = GetParam();
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const std::uint32_t normalMap = addTiltedNormalMap(builder);
    const std::uint32_t material = builder.addMaterial({.baseColor = glm::vec4(1.0f)});
    builder.json()["materials"][material]["normalTexture"] = {{"index", normalMap}};
    const glm::vec3 facing(0, 0, 1);
    const float u0 = c.mirrorU ? 1.0f : 0.0f;
    const float u1 = 1.0f - u0;
    const float vBottom = c.mirrorV ? 0.0f : 1.0f;
    const float vTop = 1.0f - vBottom;
    test::GltfBuilder::PrimitiveDesc quad;
    quad.attributes["POSITION"] =
        builder.addPositions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
    quad.attributes["NORMAL"] = builder.addNormals({facing, facing, facing, facing});
    quad.attributes["TEXCOORD_0"] =
        builder.addTexcoords({{u0, vBottom}, {u1, vBottom}, {u1, vTop}, {u0, vTop}});
    if (c.withTangents) {
        // Object space: T along +u, and w chosen so that cross(N, T) * w points up the image.
        const glm::vec3 tangent(c.mirrorU ? -1.0f : 1.0f, 0.0f, 0.0f);
        const glm::vec3 up = glm::cross(facing, tangent);
        const glm::vec3 imageUp(0.0f, c.mirrorV ? -1.0f : 1.0f, 0.0f);
        const float w = glm::dot(up, imageUp) > 0 ? 1.0f : -1.0f;
        const glm::vec4 t(tangent, w);
        quad.attributes["TANGENT"] =
            builder.addAccessor(std::vector<float>{t.x, t.y, t.z, t.w, t.x, t.y, t.z, t.w, t.x, t.y,
                                                   t.z, t.w, t.x, t.y, t.z, t.w},
                                "VEC4");
    }
    quad.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    quad.material = material;
    test::GltfBuilder::NodeDesc node{.mesh = builder.addMesh(quad)};
    if (c.mirrorInstance) {
        node.scale = glm::vec3(-1.0f, 1.0f, 1.0f);
    }
    builder.addScene({builder.addNode(node)});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "handedness.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    for (StrategyKind kind : {StrategyKind::Materials, StrategyKind::GpuCullingBundles}) {
        RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Normal);
        options.target.hdr = true;  // Reads the linear colour back.
        auto renderer = Renderer::create(*context, options);
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(*scene, kind).ok());
        renderer->renderFrame(test::frontCamera());
        auto hdr = renderer->readHdrImage();
        ASSERT_TRUE(hdr.ok());
        const std::size_t centre = (std::size_t(kSize / 2) * kSize + kSize / 2) * 4;
        const glm::vec3 normal =
            glm::vec3((*hdr)[centre], (*hdr)[centre + 1], (*hdr)[centre + 2]) * 2.0f - 1.0f;
        EXPECT_NEAR(normal.x, 0.5f * c.expectedX, 0.1f) << c.name << " " << strategyName(kind);
        EXPECT_NEAR(normal.y, 0.5f * c.expectedY, 0.1f) << c.name << " " << strategyName(kind);
        EXPECT_NEAR(normal.z, 0.707f, 0.1f) << c.name << " " << strategyName(kind);
        EXPECT_TRUE(context->checkNoErrors("rendering a normal map").ok());
    }
}

std::string handednessName(const ::testing::TestParamInfo<HandednessCase>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(
    Frames,
    NormalMapHandednessTest,
    ::testing::Values(HandednessCase{"Standard", false, false, false, false, 1, 1},
                      HandednessCase{"StandardTangents", false, false, false, true, 1, 1},
                      HandednessCase{"MirroredU", true, false, false, false, -1, 1},
                      HandednessCase{"MirroredUTangents", true, false, false, true, -1, 1},
                      HandednessCase{"MirroredV", false, true, false, false, 1, -1},
                      HandednessCase{"MirroredVTangents", false, true, false, true, 1, -1},
                      HandednessCase{"MirroredInstance", false, false, true, false, -1, 1},
                      HandednessCase{"MirroredInstanceTangents", false, false, true, true, -1, 1}),
    handednessName);

// --- Unlit ------------------------------------------------------------------------------------

TEST(UnlitTest, UnlitMaterialsOutputTheirBaseColourExactly) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const glm::vec4 color(0.2f, 0.5f, 0.8f, 1.0f);
    const std::uint32_t material = builder.addMaterial({.baseColor = color, .roughness = 0.3f});
    builder.json()["materials"][material]["extensions"]["KHR_materials_unlit"] =
        nlohmann::json::object();
    builder.json()["extensionsUsed"] = {"KHR_materials_unlit"};
    builder.addScene({addSphere(builder, material)});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "unlit.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_TRUE(scene->materials[0].unlit);
    for (StrategyKind kind : {StrategyKind::Materials, StrategyKind::Bundles,
                              StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
        auto renderer = Renderer::create(
            *context, test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(*scene, kind).ok());
        renderer->renderFrame(Camera::lookAt({0, 0, 4}, {0, 0, 0}, 0.6f, 1.0f, 0.1f, 10.0f));
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        const test::Rgba expected = {test::linearToSrgb8(color.r), test::linearToSrgb8(color.g),
                                     test::linearToSrgb8(color.b), 255};
        // Every covered pixel, lit side and dark side alike.
        for (std::uint32_t y = 24; y < 40; ++y) {
            for (std::uint32_t x = 24; x < 40; ++x) {
                ASSERT_LE(test::channelDistance(test::pixelAt(*image, x, y), expected), 1)
                    << strategyName(kind) << " at " << x << "," << y << ": "
                    << test::describe(test::pixelAt(*image, x, y));
            }
        }
    }
}

}  // namespace
}  // namespace encore::render
