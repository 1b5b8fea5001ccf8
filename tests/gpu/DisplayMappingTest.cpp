// The two ways a frame reaches the sRGB output: tone mapped by the scene shaders as they shade
// (the default: one pass) or rendered in linear HDR and mapped by a tone-mapping pass. Both
// must show the same picture. And materials without textures, which bind no texture at all
// (the uniform-only material layout), must shade as the textured path with white defaults
// would, also after one of them gains a texture.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 96;

// Pixels on the two roofs (at x = -0.55 and x = 0.55) seen by test::frontCamera().
std::pair<std::uint32_t, std::uint32_t> metalPixel() {
    return test::pixelOf(test::frontCamera(), {-0.55f, 0.3f, 0.2f}, kSize, kSize);
}
std::pair<std::uint32_t, std::uint32_t> plasticPixel() {
    return test::pixelOf(test::frontCamera(), {0.55f, 0.3f, 0.2f}, kSize, kSize);
}

// Two spheres-ish roofs (a metal and a plastic) and a textured quad, lit by the environment and
// a point light: bright highlights exercise the tone-mapping curve.
scene::SceneData litScene(bool withTexture) {
    test::GltfBuilder builder;
    const std::uint32_t metal = builder.addMaterial(
        {.baseColor = {0.9f, 0.7f, 0.3f, 1.0f}, .metallic = 1.0f, .roughness = 0.3f});
    const std::uint32_t plastic =
        builder.addMaterial({.baseColor = {0.2f, 0.4f, 0.8f, 1.0f}, .roughness = 0.2f});
    std::vector<std::uint32_t> nodes;
    for (const auto& [material, x] : {std::pair{metal, -0.55f}, std::pair{plastic, 0.55f}}) {
        test::GltfBuilder::PrimitiveDesc roof;
        roof.attributes["POSITION"] = builder.addPositions({{-0.5f, -1, 0},
                                                            {0, -1, 0.4f},
                                                            {0.5f, -1, 0},
                                                            {-0.5f, 1, 0},
                                                            {0, 1, 0.4f},
                                                            {0.5f, 1, 0}});
        roof.attributes["TEXCOORD_0"] =
            builder.addTexcoords({{0, 1}, {0.5f, 1}, {1, 1}, {0, 0}, {0.5f, 0}, {1, 0}});
        roof.indices = builder.addIndices<std::uint16_t>({0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4});
        roof.material = material;
        nodes.push_back(
            builder.addNode({.mesh = builder.addMesh(roof), .translation = glm::vec3(x, 0, 0)}));
    }
    auto& json = builder.json();
    json["extensionsUsed"] = {"KHR_lights_punctual"};
    json["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1.0, 0.9, 0.8}}, {"intensity", 8.0}}};
    test::GltfBuilder::NodeDesc lightNode{.translation = glm::vec3(0.5f, 1.0f, 2.0f)};
    const std::uint32_t light = builder.addNode(lightNode);
    json["nodes"][light]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
    nodes.push_back(light);
    builder.addScene(nodes);
    auto loaded = scene::loadSceneFromMemory(builder.toGlb(), {}, "display.glb");
    EXPECT_TRUE(loaded.ok()) << loaded.error().message;
    if (!loaded.ok()) {
        return {};
    }
    scene::SceneData scene = std::move(*loaded);
    if (withTexture) {
        // A 2x2 checker of green and white as the plastic's base colour texture.
        scene::Image image;
        image.name = "checker";
        image.width = 2;
        image.height = 2;
        image.rgba8 = {0, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 255, 0, 255};
        scene.images.push_back(image);
        scene.samplers.push_back({});
        scene.textures.push_back({scene::ImageId(std::uint32_t(scene.images.size() - 1)),
                                  scene::SamplerId(std::uint32_t(scene.samplers.size() - 1))});
        scene.materials[plastic].baseColorTexture =
            scene::TextureRef{scene::TextureId(std::uint32_t(scene.textures.size() - 1))};
    }
    return scene;
}

RendererOptions options(bool hdr, BackgroundKind background) {
    RendererOptions result = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    result.target.hdr = hdr;
    result.toneMapping.toneMapping = ToneMapping::PbrNeutral;
    result.toneMapping.exposure = 1.5f;
    result.toneMapping.background = background;
    return result;
}

image::ImageRgba8 render(const scene::SceneData& scene,
                         const RendererOptions& rendererOptions,
                         StrategyKind kind) {
    auto renderer = Renderer::create(*test::vulkanContext(), rendererOptions);
    EXPECT_TRUE(renderer.ok());
    // A transparent background needs the coverage only the HDR target keeps.
    EXPECT_EQ(renderer->target().hdr(),
              rendererOptions.target.hdr ||
                  rendererOptions.toneMapping.background == BackgroundKind::Transparent);
    EXPECT_TRUE(renderer->prepare(scene, kind).ok());
    renderer->renderFrame(test::frontCamera());
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok());
    EXPECT_TRUE(test::vulkanContext()->checkNoErrors("display mapping").ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

TEST(DisplayMappingTest, ShadersMapAsTheHdrPassDoes) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = litScene(true);
    for (BackgroundKind background : {BackgroundKind::Color, BackgroundKind::Environment}) {
        // Visibility: at one sample with a plain background it shades into the composed frame
        // (8-bit sRGB or, HDR, half floats); over an environment through its composite.
        for (StrategyKind kind :
             {StrategyKind::Bundles, StrategyKind::PipelineCache, StrategyKind::Visibility}) {
            const image::ImageRgba8 direct = render(scene, options(false, background), kind);
            const image::ImageRgba8 viaPass = render(scene, options(true, background), kind);
            ASSERT_EQ(direct.pixels.size(), viaPass.pixels.size());
            // The HDR path stores half floats before mapping: a level of rounding at most.
            EXPECT_EQ(test::differingPixels(direct, viaPass, 2), 0u)
                << "background " << int(background) << ", " << strategyName(kind);
            // Not trivially equal: the scene covers part of the frame, and it is lit.
            const image::ImageRgba8 empty =
                render(scene::SceneData{}, options(false, background), kind);
            EXPECT_GT(test::differingPixels(direct, empty, 8), std::size_t(kSize * kSize / 20));
        }
    }
}

TEST(DisplayMappingTest, TransparentBackgroundUsesTheHdrTarget) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = litScene(false);
    auto direct = Renderer::create(*context, options(false, BackgroundKind::Color));
    ASSERT_TRUE(direct.ok());
    EXPECT_FALSE(direct->target().hdr());
    ToneMappingOptions transparent = direct->toneMapping();
    transparent.background = BackgroundKind::Transparent;
    auto refused = direct->setToneMapping(transparent);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("HDR"), std::string::npos) << refused.error().message;

    const image::ImageRgba8 image =
        render(scene, options(false, BackgroundKind::Transparent), StrategyKind::Bundles);
    EXPECT_EQ(test::pixelAt(image, 0, 0)[3], 0) << "corner is background";
    const auto [x, y] = plasticPixel();
    EXPECT_EQ(test::pixelAt(image, x, y)[3], 255) << "the plastic roof";
}

TEST(DisplayMappingTest, TexturelessMaterialsBindTheUniformOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    for (bool withTexture : {false, true}) {
        const scene::SceneData scene = litScene(withTexture);
        auto renderer = Renderer::create(*context, options(false, BackgroundKind::Color));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Materials).ok());
        // One variant for the texture-less metal; the textured plastic needs a second.
        EXPECT_EQ(internals(*renderer).setup().pipelinesCreated, withTexture ? 2u : 1u);
        renderer->renderFrame(test::frontCamera());
        ASSERT_TRUE(renderer->readImage().ok());
        EXPECT_TRUE(context->checkNoErrors("texture-less materials").ok());
    }
}

// A texture-less material that gains a base colour texture moves to the textured pipelines;
// every material-sorted strategy re-groups its draws and keeps drawing without errors.
TEST(DisplayMappingTest, TexturelessMaterialGainsATexture) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = litScene(false);
    scene::Image red;
    red.name = "red";
    red.width = 1;
    red.height = 1;
    red.rgba8 = {255, 0, 0, 255};
    for (StrategyKind kind : {StrategyKind::Materials, StrategyKind::Bundles,
                              StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
        auto renderer = Renderer::create(*context, options(false, BackgroundKind::Color));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, kind).ok());
        renderer->renderFrame(test::frontCamera());
        auto before = renderer->readImage();
        ASSERT_TRUE(before.ok());
        const std::uint64_t recorded = internals(*renderer).strategy()->report().bundlesRecorded;
        // The plastic (material 1) turns red; the metal keeps its colour.
        ASSERT_TRUE(renderer->replaceBaseColorImage(scene::MaterialId{1u}, red).ok());
        renderer->renderFrame(test::frontCamera());
        auto after = renderer->readImage();
        ASSERT_TRUE(after.ok()) << strategyName(kind);
        const auto [plasticX, plasticY] = plasticPixel();
        const test::Rgba plasticBefore = test::pixelAt(*before, plasticX, plasticY);
        const test::Rgba plastic = test::pixelAt(*after, plasticX, plasticY);
        EXPECT_GT(plasticBefore[2], plasticBefore[0] + 20) << strategyName(kind);
        // Red texture times the blue factor: the blue is gone, red dominates.
        EXPECT_LT(plastic[2] + 20, plasticBefore[2]) << strategyName(kind);
        EXPECT_GT(plastic[0], plastic[2]) << strategyName(kind);
        const auto [metalX, metalY] = metalPixel();
        EXPECT_EQ(test::pixelAt(*after, metalX, metalY), test::pixelAt(*before, metalX, metalY))
            << strategyName(kind);
        if (recorded > 0) {
            EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded,
                      recorded + test::bundlesPerRecording(kind))
                << strategyName(kind);
        }
        EXPECT_TRUE(
            context
                ->checkNoErrors(std::string("texture gained, ") + std::string(strategyName(kind)))
                .ok());
    }
}

}  // namespace
}  // namespace encore::render
