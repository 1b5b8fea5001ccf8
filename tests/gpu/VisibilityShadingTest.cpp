// The visibility strategy's binning and shading (docs/visibility.md, steps 4 and 5): each
// distinct triangle of a pixel shaded once and each touched tile listed once; scenes of more bins
// than one binning dispatch lists, shaded round by round; materials of the same textures sharing
// a bin; frames of one sample shaded straight into the composed frame. VisibilityStrategyTest.cpp:
// pictures against gpu-culling-bundles, the fill rule and the composites.

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TextureFixtures.h"
#include "VisibilityTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "render/renderer/RendererCore.h"
#include "render/visibility/MaterialBins.h"
#include "render/visibility/VisibilityStrategy.h"
#include "render/visibility/VisibilityTarget.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

using test::render;
using test::triangles;

constexpr std::uint32_t kWidth = test::kVisibilityWidth;
constexpr std::uint32_t kHeight = test::kVisibilityHeight;
constexpr std::array<std::uint32_t, 2> kSampleCounts = {1, 4};
const Camera kFront = test::frontCamera(float(kWidth) / float(kHeight));

// The visibility strategy's picture of `scene` against GPU culling's (shaded, default limits).
void expectLooksLikeGpuCulling(gpu::Context& context,
                               const scene::SceneData& scene,
                               const Camera& camera,
                               std::uint32_t samples) {
    auto draw = [&](StrategyKind kind) {
        return render(context, scene, kind, camera, DebugChannel::Shaded,
                      VisibilityStrategy::kDefaultComputePixels,
                      VisibilityStrategy::kMaxWorkgroupPixels, samples);
    };
    const auto expected = draw(StrategyKind::GpuCullingBundles);
    const auto image = draw(StrategyKind::Visibility);
    test::expectVisibilityClose(expected, image);
    EXPECT_GT(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.05);
}

// Gives every material a base colour texture of its own, so that no two share a shading bin
// (render/visibility/MaterialBins.h).
void giveEachMaterialATexture(scene::SceneData& scene) {
    if (scene.samplers.empty()) {
        scene.samplers.emplace_back();
    }
    for (std::size_t material = 0; material < scene.materials.size(); ++material) {
        scene.images.push_back(
            test::solidSceneImage({std::uint8_t(60 + material * 2), 200, 255, 255}));
        scene::Texture texture;
        texture.image = scene::ImageId(std::uint32_t(scene.images.size() - 1));
        texture.sampler = scene::SamplerId(0u);
        scene.textures.push_back(texture);
        scene.materials[material].baseColorTexture =
            scene::TextureRef{scene::TextureId(std::uint32_t(scene.textures.size() - 1))};
    }
}

// A binning dispatch lists the tiles of kRoundBins bins (VisibilityTarget): a scene of 70
// meshes of a material each, every material binding a texture of its own (140 bins: three
// rounds, each listed and shaded in turn) looks as GPU culling draws it, every material's pixels
// shaded (a round left out would leave its bins' pixels unshaded). So does the same scene drawn
// with materials 40 to 69 only, whose first round lists nothing and is skipped (at one sample a
// later round writes the background).
TEST(VisibilityBinningTest, ScenesOfMoreBinsThanOneRoundShadeEveryBin) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 300;
    options.meshCount = 70;  // Mesh i has material i.
    options.materialCount = 70;
    options.textures = true;
    auto everyMaterial = test::generatedScene(options);
    giveEachMaterialATexture(everyMaterial);
    ASSERT_GT(2 * everyMaterial.materials.size(), 2 * std::size_t(VisibilityTarget::kRoundBins));
    auto laterMaterials = everyMaterial;
    for (scene::Mesh& mesh : laterMaterials.meshes) {
        for (scene::Primitive& primitive : mesh.primitives) {
            primitive.material = scene::MaterialId(40 + primitive.material.index() % 30);
        }
    }
    const Camera camera = Camera::framing(everyMaterial.bounds, float(kWidth) / float(kHeight));
    for (const auto* scene : {&everyMaterial, &laterMaterials}) {
        for (std::uint32_t samples : kSampleCounts) {
            SCOPED_TRACE(std::to_string(samples) + " samples, " +
                         (scene == &everyMaterial ? "every material" : "materials 40 to 69"));
            expectLooksLikeGpuCulling(*context, *scene, camera, samples);
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility bins in rounds").ok());
}

// Materials that bind the same textures and samplers share a shading bin, and untextured ones
// join them, each pixel's factors from the bin's table (render/visibility/MaterialBins.h): six
// generated materials, three untextured and three binding the generator's two textures, shade in
// one bin (material 1's) as GPU culling draws them; after an edit of one's factors (copied into the
// table again); and after another's base colour texture is replaced by one of its own, which
// takes it out into a bin of its own.
TEST(VisibilityBinningTest, MaterialsBindingTheSameTexturesShareABin) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 150;
    options.meshCount = 6;  // Mesh i has material i.
    options.materialCount = 6;
    options.textures = true;  // Materials 1, 3 and 5.
    const auto scene = test::generatedScene(options);
    const Camera camera = Camera::framing(scene.bounds, float(kWidth) / float(kHeight));
    auto prepared = [&](StrategyKind kind) {
        auto renderer = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, 1));
        EXPECT_TRUE(renderer.ok());
        EXPECT_TRUE(renderer->prepare(scene, kind).ok());
        return std::move(*renderer);
    };
    Renderer visibility = prepared(StrategyKind::Visibility);
    Renderer expected = prepared(StrategyKind::GpuCullingBundles);
    auto compare = [&](const char* what) {
        SCOPED_TRACE(what);
        expected.renderFrame(camera);
        visibility.renderFrame(camera);
        auto wanted = expected.readImage();
        auto image = visibility.readImage();
        ASSERT_TRUE(wanted.ok() && image.ok());
        test::expectVisibilityClose(*wanted, *image);
    };
    const auto* strategy =
        dynamic_cast<const VisibilityStrategy*>(internals(visibility).strategy());
    ASSERT_NE(strategy, nullptr);
    EXPECT_EQ(strategy->tables().bins, (std::vector<std::uint32_t>{2}));
    compare("as prepared");

    scene::Material edited = scene.materials[2];
    edited.baseColorFactor = glm::vec4(0.9f, 0.1f, 0.6f, 1.0f);
    ASSERT_TRUE(visibility.updateMaterial(scene::MaterialId(2u), edited).ok());
    ASSERT_TRUE(expected.updateMaterial(scene::MaterialId(2u), edited).ok());
    compare("material 2 edited");

    const scene::Image own = test::solidSceneImage({40, 220, 90, 255});
    ASSERT_TRUE(visibility.replaceBaseColorImage(scene::MaterialId(3u), own).ok());
    ASSERT_TRUE(expected.replaceBaseColorImage(scene::MaterialId(3u), own).ok());
    EXPECT_EQ(strategy->tables().bins, (std::vector<std::uint32_t>{2, 6}));
    compare("material 3's texture replaced");
    EXPECT_TRUE(context->checkNoErrors("visibility bins of shared bindings").ok());
}

// A bin's block holds MaterialBins::kBinMaterials materials: 70 untextured materials (one class)
// shade in two bins, materials 0-63 and 64-69, the second block's slots read at its own offset,
// as GPU culling draws them.
TEST(VisibilityBinningTest, FullBlocksOpenAnotherBin) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 300;
    options.meshCount = 70;  // Mesh i has material i.
    options.materialCount = 70;
    options.textures = false;
    const auto scene = test::generatedScene(options);
    const Camera camera = Camera::framing(scene.bounds, float(kWidth) / float(kHeight));
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, 1));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
    const auto* strategy = dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
    ASSERT_NE(strategy, nullptr);
    EXPECT_EQ(strategy->tables().bins,
              (std::vector<std::uint32_t>{0, 2 * MaterialBins::kBinMaterials}));
    expectLooksLikeGpuCulling(*context, scene, camera, 1);
    EXPECT_TRUE(context->checkNoErrors("visibility bins of full blocks").ok());
}

// At four samples a pixel's triangle is shaded once, whatever number of its samples it covers:
// into the layer of the first sample it covers, the pixel's other layers left as they were (zero
// on the first frame). Where the scene has two shading bins (a second triangle behind the
// camera, iridescent: a shader variant of its own), the triangle's bin lists each 8x8 tile it
// touches once, at one sample too (which shades into the composed frame, not the layers:
// VisibilityComposedTest); a scene of one bin is not binned (its record says every tile).
TEST(VisibilityMultisampleTest, EachTriangleOfAPixelIsShadedOnce) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::array<glm::vec3, 3> seen{glm::vec3(-3, -1.1f, -1), glm::vec3(1, -0.6f, -1),
                                        glm::vec3(-1, 1.4f, -1)};
    const std::array<glm::vec3, 3> behind{glm::vec3(-1, 0, 5), glm::vec3(1, 0, 5),
                                          glm::vec3(0, 1, 5)};
    scene::SceneData twoBins = triangles({seen, behind});
    ASSERT_EQ(twoBins.materials.size(), 2u);
    twoBins.materials[1].iridescence = scene::IridescenceExtension{.iridescenceFactor = 1.0f};
    const scene::SceneData oneBin = triangles({seen});
    for (std::uint32_t samples : kSampleCounts) {
        for (const bool binned : {false, true}) {
            SCOPED_TRACE(std::to_string(samples) + " samples, " + (binned ? "binned" : "one bin"));
            auto renderer =
                Renderer::create(*context, test::pixelTestOptions(kWidth, kHeight, samples));
            ASSERT_TRUE(renderer.ok());
            ASSERT_TRUE(
                renderer->prepare(binned ? twoBins : oneBin, StrategyKind::Visibility).ok());
            renderer->renderFrame(kFront);
            auto image = renderer->readImage();
            ASSERT_TRUE(image.ok());
            const auto* visibility =
                dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
            ASSERT_NE(visibility, nullptr);
            EXPECT_EQ(visibility->tables().bins.size(), binned ? 2u : 1u);
            const std::uint32_t binCount = visibility->tables().binCount;
            auto bins = gpu::readBuffer(*context, visibility->bins(), 0,
                                        binCount * VisibilityStrategy::kBinRecordBytes);
            ASSERT_TRUE(bins.ok());
            std::uint64_t tilesListed = 0;
            std::uint32_t everyTile = 0;
            for (std::uint32_t bin = 0; bin < binCount; ++bin) {
                std::array<std::uint32_t, 4> record{};
                std::memcpy(record.data(), bins->data() + bin * VisibilityStrategy::kBinRecordBytes,
                            sizeof(record));
                tilesListed += record[0];
                everyTile += record[3];
            }
            EXPECT_EQ(everyTile, binned ? 0u : 1u);
            std::vector<std::vector<float>> layers;
            for (std::uint32_t layer = 0; samples > 1 && layer < samples; ++layer) {
                auto texels =
                    gpu::readTextureRgba16Float(*context, visibility->shadedColour(), 0, layer);
                ASSERT_TRUE(texels.ok());
                layers.push_back(std::move(*texels));
            }
            const auto background = test::pixelAt(*image, 0, 0);
            std::uint64_t touched = 0;
            std::set<std::pair<std::uint32_t, std::uint32_t>> tiles;
            std::uint64_t shadedOnce = 0;
            std::uint64_t shadedTexels = 0;
            for (std::uint32_t y = 0; y < image->height; ++y) {
                for (std::uint32_t x = 0; x < image->width; ++x) {
                    std::uint32_t shaded = 0;
                    for (const std::vector<float>& layer : layers) {
                        shaded += layer[(std::size_t(y) * image->width + x) * 4 + 3] != 0.0f;
                    }
                    shadedTexels += shaded;
                    if (test::pixelAt(*image, x, y) != background) {
                        ++touched;
                        tiles.insert({x / 8, y / 8});
                        shadedOnce += shaded == 1;
                    }
                }
            }
            EXPECT_GT(touched, 500u);
            if (samples > 1) {
                EXPECT_EQ(shadedOnce, touched);
                EXPECT_EQ(shadedTexels, touched);
            }
            EXPECT_EQ(tilesListed, binned ? tiles.size() : 0u);
        }
    }
}

// At one sample a frame composed in compute (a plain background) is shaded into place, its
// uncovered pixels written by the shading of its one bin (no binning, no composition pass): its
// covered pixels are those the render-pass composite draws over an environment (the shaded
// texture's half floats round a level at most), and the others hold the background exactly. Its
// shaded texture stays unwritten (zero on the first frame), which the composite's frame fills.
TEST(VisibilityComposedTest, ShadedIntoPlaceAsTheCompositeDrawsIt) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = test::generatedVisibilityScene(scene::SceneLayout::Grid, 200);
    const Camera camera = Camera::framing(scene.bounds, float(kWidth) / float(kHeight));
    auto frame = [&](BackgroundKind background, std::vector<std::uint8_t>* visibility,
                     std::size_t* shadedTexels) {
        RendererOptions options = test::pixelTestOptions(kWidth, kHeight, 1);
        options.toneMapping.background = background;
        auto renderer = Renderer::create(*context, options);
        EXPECT_TRUE(renderer.ok());
        EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
        renderer->renderFrame(camera);
        if (visibility) {
            const auto* strategy =
                dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
            auto bytes = gpu::readBuffer(*context, strategy->visibilityBuffer(), 0,
                                         std::uint64_t(kWidth) * kHeight * 8);
            EXPECT_TRUE(bytes.ok());
            *visibility = bytes.ok() ? std::move(*bytes) : std::vector<std::uint8_t>{};
        }
        const auto* strategy =
            dynamic_cast<const VisibilityStrategy*>(internals(*renderer).strategy());
        auto texels = gpu::readTextureRgba16Float(*context, strategy->shadedColour(), 0, 0);
        EXPECT_TRUE(texels.ok());
        *shadedTexels = 0;
        for (std::size_t i = 3; texels.ok() && i < texels->size(); i += 4) {
            *shadedTexels += (*texels)[i] != 0.0f;
        }
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok());
        return image.ok() ? std::move(*image) : image::ImageRgba8{};
    };
    std::vector<std::uint8_t> visibility;
    std::size_t composedTexels = 0;
    std::size_t drawnTexels = 0;
    const image::ImageRgba8 composed = frame(BackgroundKind::Color, &visibility, &composedTexels);
    const image::ImageRgba8 drawn = frame(BackgroundKind::Environment, nullptr, &drawnTexels);
    EXPECT_EQ(composedTexels, 0u);
    ASSERT_EQ(visibility.size(), std::size_t(kWidth) * kHeight * 8);
    ASSERT_EQ(composed.pixels.size(), drawn.pixels.size());
    // The background: a pixel of the composed frame that nothing covers.
    std::optional<std::array<std::uint8_t, 4>> background;
    std::size_t covered = 0;
    std::size_t apart = 0;
    std::size_t otherBackground = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < kWidth; ++x) {
            const std::size_t pixel = std::size_t(y) * kWidth + x;
            std::uint32_t depthWord = 0;
            std::memcpy(&depthWord, visibility.data() + pixel * 8 + 4, 4);
            const auto color = test::pixelAt(composed, x, y);
            if (depthWord == 0) {
                background = background.value_or(color);
                otherBackground += color != *background;
                continue;
            }
            ++covered;
            const auto expected = test::pixelAt(drawn, x, y);
            for (int c = 0; c < 4; ++c) {
                apart += std::abs(int(color[c]) - int(expected[c])) > 1;
            }
        }
    }
    EXPECT_GT(covered, std::size_t(kWidth) * kHeight / 20);
    EXPECT_EQ(drawnTexels, covered);
    ASSERT_TRUE(background.has_value());
    EXPECT_EQ(otherBackground, 0u);
    EXPECT_EQ(apart, 0u);
    EXPECT_TRUE(context->checkNoErrors("visibility shaded into place").ok());
}

}  // namespace
}  // namespace encore::render
