// KHR_materials_transmission, volume and dispersion on the GPU: a glass quad in front of unlit
// coloured quads shows them through it (tinted by a volume's attenuation colour, blurred by
// roughness, split per channel by dispersion) in every strategy that shades materials, and a
// scene without transmission makes no copy and records no extra bundle.
//
// The scenes render without image-based lighting and without lights: an opaque surface is then
// black, and a transmissive one shows only what lies behind it (less the Fresnel reflectance),
// so the expectations are the background's own colours.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Renderer.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
const glm::vec3 kFacing(0.0f, 0.0f, 1.0f);

struct GlassDesc {
    std::optional<nlohmann::json> transmission = nlohmann::json{{"transmissionFactor", 1.0}};
    std::optional<nlohmann::json> volume;
    std::optional<nlohmann::json> dispersion;
    float roughness = 0.0f;
    // 1-pixel textures (RGBA) for transmissionTexture and thicknessTexture.
    std::optional<std::array<std::uint8_t, 4>> transmissionTexture;
    std::optional<std::array<std::uint8_t, 4>> thicknessTexture;
};

// A 1x1 PNG embedded through a bufferView; returns the texture index.
std::uint32_t addPixelTexture(test::GltfBuilder& builder, std::array<std::uint8_t, 4> rgba) {
    image::ImageRgba8 pixel{1, 1, {rgba.begin(), rgba.end()}};
    const auto png = image::encodePng(pixel);
    EXPECT_TRUE(png.ok());
    const std::uint32_t view = builder.addBufferView(*png);
    auto& json = builder.json();
    json["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
    json["textures"].push_back({{"source", json["images"].size() - 1}});
    return static_cast<std::uint32_t>(json["textures"].size() - 1);
}

// A quad from (left, bottom) to (right, top) at depth z.
std::uint32_t addQuad(test::GltfBuilder& builder,
                      glm::vec2 min,
                      glm::vec2 max,
                      float z,
                      std::uint32_t material) {
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions(
        {{min.x, min.y, z}, {max.x, min.y, z}, {max.x, max.y, z}, {min.x, max.y, z}});
    primitive.attributes["NORMAL"] = builder.addNormals({kFacing, kFacing, kFacing, kFacing});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    primitive.material = material;
    return builder.addNode({.mesh = builder.addMesh(primitive)});
}

std::uint32_t addUnlit(test::GltfBuilder& builder, glm::vec4 color) {
    const std::uint32_t material = builder.addMaterial({.baseColor = color});
    builder.json()["materials"][material]["extensions"]["KHR_materials_unlit"] =
        nlohmann::json::object();
    return material;
}

// Unlit red on the left half and blue on the right half at z = -1, behind a glass quad at z = 0
// (without `glass`: nothing in front).
scene::SceneData glassScene(std::optional<GlassDesc> glass) {
    test::GltfBuilder builder;
    builder.json()["extensionsUsed"] = {"KHR_materials_unlit"};
    std::vector<std::uint32_t> nodes = {
        addQuad(builder, {-4, -4}, {0, 4}, -1.0f, addUnlit(builder, {0.8f, 0.1f, 0.1f, 1})),
        addQuad(builder, {0, -4}, {4, 4}, -1.0f, addUnlit(builder, {0.1f, 0.1f, 0.8f, 1}))};
    if (glass) {
        const std::uint32_t material =
            builder.addMaterial({.baseColor = {1, 1, 1, 1}, .roughness = glass->roughness});
        auto use = [&](const char* name, const std::optional<nlohmann::json>& value) {
            if (value) {
                builder.json()["materials"][material]["extensions"][name] = *value;
                builder.json()["extensionsUsed"].push_back(name);
            }
        };
        use("KHR_materials_transmission", glass->transmission);
        use("KHR_materials_volume", glass->volume);
        use("KHR_materials_dispersion", glass->dispersion);
        auto& materialJson = builder.json()["materials"][material];
        if (glass->transmissionTexture) {
            materialJson["extensions"]["KHR_materials_transmission"]["transmissionTexture"] = {
                {"index", addPixelTexture(builder, *glass->transmissionTexture)}};
        }
        if (glass->thicknessTexture) {
            materialJson["extensions"]["KHR_materials_volume"]["thicknessTexture"] = {
                {"index", addPixelTexture(builder, *glass->thicknessTexture)}};
        }
        nodes.push_back(addQuad(builder, {-1.5f, -1.5f}, {1.5f, 1.5f}, 0.0f, material));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "glass.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene.ok() && scene->warnings.empty());
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

RendererOptions unlitOptions() {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.lighting.imageBasedLighting = false;
    options.lighting.punctualLights = false;
    options.toneMapping.backgroundColor = glm::vec3(0.0f);
    return options;
}

struct Rendered {
    image::ImageRgba8 image;
    FrameResult frame;
    std::uint64_t bundlesRecorded = 0;
};

Rendered render(const scene::SceneData& scene,
                StrategyChoice strategy = {StrategyKind::Materials, false},
                RendererOptions options = unlitOptions()) {
    gpu::Context* context = test::vulkanContext();
    if (!context) {
        ADD_FAILURE() << "no Vulkan context";
        return {};
    }
    auto renderer = Renderer::create(*context, options);
    EXPECT_TRUE(renderer.ok());
    auto prepared = renderer->prepare(scene, strategy.kind, strategy.bundle);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    if (!prepared) {
        return {};
    }
    Rendered result;
    result.frame = renderer->renderFrame(test::frontCamera());
    result.frame = renderer->renderFrame(test::frontCamera());  // Bundles replay, not record.
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    EXPECT_TRUE(context->checkNoErrors("transmission").ok());
    if (image) {
        result.image = std::move(*image);
    }
    result.bundlesRecorded = internals(*renderer).strategy()
                                 ? internals(*renderer).strategy()->report().bundlesRecorded
                                 : 0;
    return result;
}

test::Rgba pixel(const image::ImageRgba8& image, glm::vec3 point) {
    if (image.width != kSize) {
        return {};
    }
    const auto [x, y] = test::pixelOf(test::frontCamera(), point, kSize, kSize);
    return test::pixelAt(image, x, y);
}

// Linear value of an 8-bit sRGB channel.
double linear(std::uint8_t value) {
    const double c = value / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Points on the glass in front of the red half and of the blue half.
const glm::vec3 kRedSide(-0.8f, 0.0f, 0.0f);
const glm::vec3 kBlueSide(0.8f, 0.0f, 0.0f);

TEST(TransmissionRenderTest, OpaqueQuadHidesTheBackgroundAndGlassShowsIt) {
    ENCORE_REQUIRE_VULKAN(context);
    GlassDesc opaque;
    opaque.transmission.reset();
    const Rendered hidden = render(glassScene(opaque));
    EXPECT_LE(pixel(hidden.image, kRedSide)[0], 2) << test::describe(pixel(hidden.image, kRedSide));

    const Rendered seen = render(glassScene(GlassDesc{}));
    // Through smooth glass at normal incidence: the background less about 4% reflectance.
    const test::Rgba red = pixel(seen.image, kRedSide);
    const test::Rgba blue = pixel(seen.image, kBlueSide);
    EXPECT_NEAR(linear(red[0]), 0.8 * 0.96, 0.03) << test::describe(red);
    EXPECT_NEAR(linear(red[2]), 0.1 * 0.96, 0.02) << test::describe(red);
    EXPECT_NEAR(linear(blue[2]), 0.8 * 0.96, 0.03) << test::describe(blue);
    EXPECT_NEAR(linear(blue[0]), 0.1 * 0.96, 0.02) << test::describe(blue);
    EXPECT_EQ(seen.frame.transmissionCopies, 1u);
}

TEST(TransmissionRenderTest, VolumeAttenuationTintsWhatIsBehind) {
    ENCORE_REQUIRE_VULKAN(context);
    GlassDesc glass;
    // One unit through the volume (normal incidence, unscaled): attenuationColor exactly.
    glass.volume = nlohmann::json{{"thicknessFactor", 1.0},
                                  {"attenuationDistance", 1.0},
                                  {"attenuationColor", {0.25, 1.0, 0.5}}};
    const Rendered tinted = render(glassScene(glass));
    const test::Rgba red = pixel(tinted.image, kRedSide);
    const test::Rgba blue = pixel(tinted.image, kBlueSide);
    EXPECT_NEAR(linear(red[0]), 0.8 * 0.25 * 0.96, 0.02) << test::describe(red);
    EXPECT_NEAR(linear(red[1]), 0.1 * 0.96, 0.02) << test::describe(red);
    EXPECT_NEAR(linear(blue[2]), 0.8 * 0.5 * 0.96, 0.03) << test::describe(blue);

    // Twice the distance, half the absorption: the square root of the colour.
    glass.volume->at("attenuationDistance") = 2.0;
    const test::Rgba lighter = pixel(render(glassScene(glass)).image, kRedSide);
    EXPECT_NEAR(linear(lighter[0]), 0.8 * 0.5 * 0.96, 0.03) << test::describe(lighter);
}

TEST(TransmissionRenderTest, TransmissionAndThicknessTexturesScaleTheirFactors) {
    ENCORE_REQUIRE_VULKAN(context);
    // Red 0 in the transmission texture: nothing passes, the glass is an opaque black dielectric.
    GlassDesc blocked;
    blocked.transmissionTexture = std::array<std::uint8_t, 4>{0, 255, 255, 255};
    const test::Rgba dark = pixel(render(glassScene(blocked)).image, kRedSide);
    EXPECT_LE(dark[0], 2) << test::describe(dark);
    // Red 128 (linear data, about 0.5): half of the background.
    GlassDesc half;
    half.transmissionTexture = std::array<std::uint8_t, 4>{128, 0, 0, 255};
    const test::Rgba halfRed = pixel(render(glassScene(half)).image, kRedSide);
    EXPECT_NEAR(linear(halfRed[0]), 0.8 * 0.96 * 128.0 / 255.0, 0.03) << test::describe(halfRed);

    // Green 0 in the thickness texture: thin-walled, no absorption despite the volume.
    GlassDesc thin;
    thin.volume = nlohmann::json{{"thicknessFactor", 1.0},
                                 {"attenuationDistance", 1.0},
                                 {"attenuationColor", {0.25, 1.0, 0.5}}};
    thin.thicknessTexture = std::array<std::uint8_t, 4>{255, 0, 255, 255};
    const test::Rgba clear = pixel(render(glassScene(thin)).image, kRedSide);
    EXPECT_NEAR(linear(clear[0]), 0.8 * 0.96, 0.03) << test::describe(clear);
}

// The contrast across the red/blue edge behind the glass, a few pixels to each side.
double edgeContrast(const image::ImageRgba8& image) {
    const test::Rgba left = pixel(image, {-0.25f, 0.0f, 0.0f});
    const test::Rgba right = pixel(image, {0.25f, 0.0f, 0.0f});
    return (linear(left[0]) - linear(right[0])) + (linear(right[2]) - linear(left[2]));
}

TEST(TransmissionRenderTest, RoughGlassIsBlurrierThanSmoothGlass) {
    ENCORE_REQUIRE_VULKAN(context);
    const double smooth = edgeContrast(render(glassScene(GlassDesc{})).image);
    GlassDesc frosted;
    frosted.roughness = 0.9f;  // Mip level 9 of 10: 2 x 2 texels over the whole view.
    const double rough = edgeContrast(render(glassScene(frosted)).image);
    EXPECT_GT(smooth, 1.2);  // Nearly the full 0.7 + 0.7 of the background.
    EXPECT_LT(rough, 0.5 * smooth) << "smooth " << smooth << ", rough " << rough;
    EXPECT_GT(rough, 0.0);  // Still red on the left and blue on the right.
}

TEST(TransmissionRenderTest, ThickGlassRefractsAndDispersionSplitsTheChannels) {
    ENCORE_REQUIRE_VULKAN(context);
    // Seen obliquely, a thick volume shifts what is seen behind it; dispersion shifts each
    // channel by its own amount, so near the edge red and blue no longer come from one point.
    GlassDesc thick;
    thick.volume = nlohmann::json{{"thicknessFactor", 2.0}};
    GlassDesc dispersive = thick;
    dispersive.dispersion = nlohmann::json{{"dispersion", 10.0}};
    const Camera oblique = Camera::lookAt({2.0f, 0.0f, 2.5f}, {0.0f, 0.0f, 0.0f},
                                          glm::half_pi<float>(), 1.0f, 0.1f, 10.0f);
    auto renderFrom = [&](const GlassDesc& glass) {
        gpu::Context* context = test::vulkanContext();
        auto renderer = Renderer::create(*context, unlitOptions());
        EXPECT_TRUE(renderer.ok());
        const scene::SceneData scene = glassScene(glass);
        EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Materials).ok());
        renderer->renderFrame(oblique);
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok());
        return image.ok() ? std::move(*image) : image::ImageRgba8{};
    };
    GlassDesc thin;
    const image::ImageRgba8 straight = renderFrom(thin);
    const image::ImageRgba8 refracted = renderFrom(thick);
    const image::ImageRgba8 split = renderFrom(dispersive);
    ASSERT_EQ(straight.width, kSize);
    int changed = 0;
    int dispersed = 0;
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            changed += test::channelDistance(test::pixelAt(straight, x, y),
                                             test::pixelAt(refracted, x, y)) > 40;
            dispersed += test::channelDistance(test::pixelAt(refracted, x, y),
                                               test::pixelAt(split, x, y)) > 20;
        }
    }
    EXPECT_GT(changed, 20) << "refraction through the volume moved the edge";
    EXPECT_GT(dispersed, 5) << "dispersion moved the channels apart";
}

TEST(TransmissionRenderTest, EveryMaterialStrategyDrawsTheSameGlass) {
    ENCORE_REQUIRE_VULKAN(context);
    GlassDesc glass;
    glass.volume = nlohmann::json{{"thicknessFactor", 1.0},
                                  {"attenuationDistance", 1.0},
                                  {"attenuationColor", {0.25, 1.0, 0.5}}};
    const scene::SceneData scene = glassScene(glass);
    const Rendered expected = render(scene);
    ASSERT_EQ(expected.image.width, kSize);
    for (const StrategyChoice& choice : test::everyStrategyChoice()) {
        if (!test::shadesMaterials(choice.kind)) {
            continue;  // Their frames shade no materials at all (docs/materials.md).
        }
        SCOPED_TRACE(std::string(strategyName(choice.kind)) + (choice.bundle ? "+bundle" : ""));
        const Rendered actual = render(scene, choice);
        ASSERT_EQ(actual.image.width, kSize);
        EXPECT_EQ(actual.frame.transmissionCopies, 1u);
        EXPECT_EQ(test::differingPixels(expected.image, actual.image, 2), 0u);
    }
}

TEST(TransmissionRenderTest, SceneWithoutTransmissionCopiesNothingAndRecordsNoExtraBundle) {
    ENCORE_REQUIRE_VULKAN(context);
    GlassDesc opaque;
    opaque.transmission.reset();
    const scene::SceneData plain = glassScene(opaque);
    const scene::SceneData glass = glassScene(GlassDesc{});
    const StrategyChoice bundles{StrategyKind::Bundles, false};
    const Rendered without = render(plain, bundles);
    const Rendered with = render(glass, bundles);
    EXPECT_EQ(without.frame.transmissionCopies, 0u);
    EXPECT_EQ(with.frame.transmissionCopies, 1u);
    // One bundle (opaque geometry) against two (and the transmission one), each recorded once
    // over two frames; the second frame only replays them.
    EXPECT_EQ(without.bundlesRecorded, 1u);
    EXPECT_EQ(with.bundlesRecorded, 2u);
    EXPECT_EQ(without.frame.counters.executeBundles, 1u);
    EXPECT_EQ(with.frame.counters.executeBundles, 2u);
}

TEST(TransmissionRenderTest, MultisampledAndHdrTargetsShowTheBackgroundToo) {
    ENCORE_REQUIRE_VULKAN(context);
    for (const bool hdr : {false, true}) {
        SCOPED_TRACE(hdr ? "hdr" : "sRGB");
        RendererOptions options = unlitOptions();
        options.target.sampleCount = 4;
        options.target.hdr = hdr;
        const Rendered seen =
            render(glassScene(GlassDesc{}), {StrategyKind::Bundles, false}, options);
        const test::Rgba red = pixel(seen.image, kRedSide);
        EXPECT_NEAR(linear(red[0]), 0.8 * 0.96, 0.03) << test::describe(red);
        EXPECT_NEAR(linear(red[2]), 0.1 * 0.96, 0.02) << test::describe(red);
    }
}

}  // namespace
}  // namespace encore::render
