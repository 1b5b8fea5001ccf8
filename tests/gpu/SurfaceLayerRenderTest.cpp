// KHR_materials_iridescence and KHR_materials_anisotropy in pixels, on a square facing the
// camera: a thin film colours a grey metal and vanishes with its thickness or its texture; an
// anisotropic highlight stretches along the anisotropy direction, turned by the rotation or by
// the direction texture, and a strength of 0 changes nothing. The `visibility` strategy's
// compute resolve shades as the fragment path does.

#include <gtest/gtest.h>

#include <algorithm>
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
using nlohmann::json;
using EditMaterial = std::function<void(test::GltfBuilder&, json&)>;

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

// A 1x1 PNG texture of `rgba`; returns its index.
std::uint32_t addPixelTexture(test::GltfBuilder& builder, std::array<std::uint8_t, 4> rgba) {
    image::ImageRgba8 pixel{1, 1, {rgba.begin(), rgba.end()}};
    const auto png = image::encodePng(pixel);
    EXPECT_TRUE(png.ok());
    auto& document = builder.json();
    document["images"].push_back(
        {{"bufferView", builder.addBufferView(*png)}, {"mimeType", "image/png"}});
    document["textures"].push_back({{"source", document["images"].size() - 1}});
    return std::uint32_t(document["textures"].size() - 1);
}

struct Frame {
    std::vector<float> rgba;  // Linear HDR.
    glm::vec3 at(std::uint32_t x, std::uint32_t y) const {
        const std::size_t i = (std::size_t(y) * kSize + x) * 4;
        return {rgba[i], rgba[i + 1], rgba[i + 2]};
    }
};

struct SquareScene {
    test::GltfBuilder::MaterialDesc material;
    EditMaterial edit;
    bool light = false;  // A point light 1 above the centre; image-based light off.
};

// A 4x4 square at z = 0 facing +Z (TEXCOORD_0: u along +x, v along -y) under the furnace, seen
// from straight above, read back as linear HDR.
Frame renderSquare(const SquareScene& desc, StrategyKind strategy = StrategyKind::Bundles) {
    gpu::Context* context = test::vulkanContext();
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc square = builder.addFacingQuad({-2, -2}, {2, 2});
    square.material = builder.addMaterial(desc.material);
    if (desc.edit) {
        desc.edit(builder, builder.json()["materials"][*square.material]);
    }
    std::vector<std::uint32_t> nodes = {builder.addNode({.mesh = builder.addMesh(square)})};
    if (desc.light) {
        auto& document = builder.json();
        document["extensionsUsed"].push_back("KHR_lights_punctual");
        document["extensions"]["KHR_lights_punctual"]["lights"] = {
            {{"type", "point"}, {"intensity", 4.0}}};
        nodes.push_back(builder.addNode({.translation = glm::vec3(0, 0, 1)}));
        document["nodes"][nodes.back()]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "square.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene.ok() && scene->warnings.empty());
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.target.hdr = true;
    options.environment = furnaceEnvironment();
    options.lighting.imageBasedLighting = !desc.light;
    auto renderer = Renderer::create(*context, options);
    EXPECT_TRUE(renderer.ok());
    if (!scene || !renderer) {
        return {std::vector<float>(std::size_t(kSize) * kSize * 4)};
    }
    EXPECT_TRUE(renderer->prepare(*scene, strategy).ok());
    renderer->renderFrame(
        Camera::lookAt({0, 0, 3}, {0, 0, 0}, glm::radians(70.0f), 1.0f, 0.1f, 10.0f));
    auto hdr = renderer->readHdrImage();
    EXPECT_TRUE(hdr.ok());
    EXPECT_TRUE(context->checkNoErrors("rendering a square").ok());
    return {hdr.ok() ? std::move(*hdr) : std::vector<float>(std::size_t(kSize) * kSize * 4)};
}

float largestDifference(const Frame& a, const Frame& b) {
    float largest = 0.0f;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        largest = std::max(largest, std::abs(a.rgba[i] - b.rgba[i]));
    }
    return largest;
}

float channelSpread(const glm::vec3& c) {
    return std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b});
}

const test::GltfBuilder::MaterialDesc kGreyMirror{.baseColor = {0.5f, 0.5f, 0.5f, 1.0f},
                                                  .metallic = 1.0f,
                                                  .roughness = 0.0f};

// KHR_materials_iridescence on the grey metal mirror, thickness `maximum` nanometres unless
// `edit` changes more.
SquareScene filmOn(float maximum, float minimum = 100.0f, EditMaterial more = {}) {
    return {kGreyMirror, [=](test::GltfBuilder& builder, json& material) {
                material["extensions"]["KHR_materials_iridescence"] = {
                    {"iridescenceFactor", 1.0},
                    {"iridescenceIor", 1.33},
                    {"iridescenceThicknessMinimum", minimum},
                    {"iridescenceThicknessMaximum", maximum}};
                if (more) {
                    more(builder, material["extensions"]["KHR_materials_iridescence"]);
                }
            }};
}

TEST(IridescenceRenderTest, AThinFilmColoursAGreyMetalAndVanishesWithItsThickness) {
    ENCORE_REQUIRE_VULKAN(context);
    const Frame plain = renderSquare({kGreyMirror});
    const Frame film400 = renderSquare(filmOn(400.0f));
    const Frame film250 = renderSquare(filmOn(250.0f));
    const glm::vec3 grey = plain.at(kSize / 2, kSize / 2);
    const glm::vec3 colour400 = film400.at(kSize / 2, kSize / 2);
    const glm::vec3 colour250 = film250.at(kSize / 2, kSize / 2);
    // Under a white furnace the bare metal reflects its grey; the film tints it, differently
    // for another thickness, and reflects no more than all the light.
    EXPECT_LT(channelSpread(grey), 1e-3f) << grey.r << " " << grey.g << " " << grey.b;
    EXPECT_GT(channelSpread(colour400), 0.05f)
        << colour400.r << " " << colour400.g << " " << colour400.b;
    EXPECT_GT(glm::length(colour400 - colour250), 0.05f);
    EXPECT_LE(std::max({colour400.r, colour400.g, colour400.b}), 1.01f);

    // No thickness, or a factor texture of 0: the bare metal again.
    EXPECT_LT(largestDifference(renderSquare(filmOn(0.0f, 0.0f)), plain), 1e-3f);
    const Frame masked = renderSquare(filmOn(400.0f, 100.0f, [](auto& builder, json& film) {
        film["iridescenceTexture"] = {{"index", addPixelTexture(builder, {0, 0, 0, 255})}};
    }));
    EXPECT_LT(largestDifference(masked, plain), 1e-3f);
}

// The thickness texture's green channel picks between the minimum and the maximum.
TEST(IridescenceRenderTest, TheThicknessTextureMixesMinimumAndMaximum) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto thicknessTexture = [](std::uint8_t green) {
        return [green](test::GltfBuilder& builder, json& film) {
            film["iridescenceThicknessTexture"] = {
                {"index", addPixelTexture(builder, {255, green, 255, 255})}};
        };
    };
    const Frame atMinimum = renderSquare(filmOn(600.0f, 250.0f, thicknessTexture(0)));
    const Frame atMaximum = renderSquare(filmOn(600.0f, 250.0f, thicknessTexture(255)));
    EXPECT_LT(largestDifference(atMinimum, renderSquare(filmOn(250.0f))), 1e-3f);
    EXPECT_LT(largestDifference(atMaximum, renderSquare(filmOn(600.0f))), 1e-3f);
    EXPECT_GT(largestDifference(atMinimum, atMaximum), 0.05f);
}

// A point light's highlight on a metal plane: how far it reaches along x and along y through
// the centre (pixels brighter than half the peak).
struct Highlight {
    int alongX = 0;
    int alongY = 0;
};

Highlight highlightOf(const Frame& frame) {
    const float peak = frame.at(kSize / 2, kSize / 2).r;
    Highlight extent;
    for (std::uint32_t i = 0; i < kSize; ++i) {
        extent.alongX += frame.at(i, kSize / 2).r > 0.5f * peak ? 1 : 0;
        extent.alongY += frame.at(kSize / 2, i).r > 0.5f * peak ? 1 : 0;
    }
    return extent;
}

SquareScene anisotropicPlane(float strength, float rotation, EditMaterial more = {}) {
    return {{.baseColor = glm::vec4(1.0f), .metallic = 1.0f, .roughness = 0.3f},
            [=](test::GltfBuilder& builder, json& material) {
                material["extensions"]["KHR_materials_anisotropy"] = {
                    {"anisotropyStrength", strength}, {"anisotropyRotation", rotation}};
                if (more) {
                    more(builder, material["extensions"]["KHR_materials_anisotropy"]);
                }
            },
            true};
}

TEST(AnisotropyRenderTest, AHighlightStretchesAlongTheAnisotropyDirection) {
    ENCORE_REQUIRE_VULKAN(context);
    const Highlight isotropic =
        highlightOf(renderSquare({{.metallic = 1.0f, .roughness = 0.3f}, {}, true}));
    const Highlight alongTangent = highlightOf(renderSquare(anisotropicPlane(0.8f, 0.0f)));
    const Highlight turned =
        highlightOf(renderSquare(anisotropicPlane(0.8f, glm::half_pi<float>())));
    EXPECT_LE(std::abs(isotropic.alongX - isotropic.alongY), 1);
    // The tangent (growing u) runs along +x; a quarter turn takes it to y.
    EXPECT_GT(alongTangent.alongX, alongTangent.alongY + 4)
        << alongTangent.alongX << " x " << alongTangent.alongY;
    EXPECT_GT(alongTangent.alongX, isotropic.alongX);
    EXPECT_GT(turned.alongY, turned.alongX + 4) << turned.alongX << " x " << turned.alongY;
}

TEST(AnisotropyRenderTest, StrengthZeroIsIsotropicAndTheTextureTurnsTheDirection) {
    ENCORE_REQUIRE_VULKAN(context);
    const Frame isotropic = renderSquare({{.metallic = 1.0f, .roughness = 0.3f}, {}, true});
    EXPECT_LT(largestDifference(renderSquare(anisotropicPlane(0.0f, 1.0f)), isotropic), 1e-3f);
    // Direction (0, 1) in the texture (red 0.5, green 1) with full strength (blue 1) is the
    // tangent turned a quarter, as the rotation turns it.
    const Frame textured = renderSquare(anisotropicPlane(0.8f, 0.0f, [](auto& builder, json& e) {
        e["anisotropyTexture"] = {{"index", addPixelTexture(builder, {128, 255, 255, 255})}};
    }));
    const Frame rotated = renderSquare(anisotropicPlane(0.8f, glm::half_pi<float>()));
    EXPECT_LT(largestDifference(textured, rotated), 0.02f * rotated.at(kSize / 2, kSize / 2).r);
}

// The compute resolve of `visibility` shades both extensions as the fragment shader does, under
// image-based light (the film) and a punctual light (the anisotropy).
TEST(SurfaceLayerStrategyTest, VisibilityShadesAsTheFragmentPathDoes) {
    ENCORE_REQUIRE_VULKAN(context);
    for (const SquareScene& desc : {filmOn(400.0f), anisotropicPlane(0.8f, 0.5f)}) {
        const Frame fragment = renderSquare(desc, StrategyKind::Bundles);
        const Frame compute = renderSquare(desc, StrategyKind::Visibility);
        EXPECT_LT(largestDifference(fragment, compute), 0.01f);
    }
}

}  // namespace
}  // namespace encore::render
