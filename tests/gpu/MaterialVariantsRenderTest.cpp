// KHR_materials_variants on the GPU: selecting a variant changes what the materials strategies
// draw exactly as the variant maps it (another factor, a blended material, a textured one with a
// normal map), leaves the other primitive alone, and changes material bindings only: for every
// strategy the GPU scene is uploaded once and its bytes stay, and bundles record again.

#include <gtest/gtest.h>

#include <filesystem>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "VariantFixture.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"
#include "render/GpuScene.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

// The strategies that shade glTF materials (the earlier ones draw every primitive alike).
bool drawsMaterials(StrategyKind kind) {
    return kind == StrategyKind::Materials || kind == StrategyKind::Bundles ||
           cullsOnTheGpu(kind) || kind == StrategyKind::Visibility;
}

test::Rgba encode(const glm::vec3& linear) {
    return {test::linearToSrgb8(linear.r), test::linearToSrgb8(linear.g),
            test::linearToSrgb8(linear.b), 255};
}

test::Rgba pixelOf(const image::ImageRgba8& image, const glm::vec3& point) {
    const auto [x, y] = test::pixelOf(test::frontCamera(), point, kSize, kSize);
    return test::pixelAt(image, x, y);
}

scene::SceneData loadQuads() {
    auto scene = scene::loadSceneFromMemory(test::variantQuads().toGlb(), {}, "variants.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

std::optional<scene::VariantId> variantOf(int index) {
    return index < 0 ? std::nullopt : std::optional(scene::VariantId(std::size_t(index)));
}

TEST(MaterialVariantsRenderTest, ASwitchChangesMaterialBindingsOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = loadQuads();
    ASSERT_EQ(scene.variants.size(), 4u);
    for (const StrategyChoice& choice : test::everyStrategyChoice()) {
        SCOPED_TRACE(std::string(strategyName(choice.kind)) + (choice.bundle ? "+bundle" : ""));
        auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, choice.kind, choice.bundle).ok());
        const GpuScene* gpuScene = internals(*renderer).gpuScene();
        const std::uint64_t uploaded = internals(*renderer).uploadedBytes();
        EXPECT_GT(uploaded, 0u);
        std::optional<image::ImageRgba8> first;
        int selected = -1;
        // Every variant, back to the default, and a variant straight after the default.
        for (int variant : {-1, 0, 1, 2, 3, -1, 2, 2}) {
            SCOPED_TRACE("variant " + std::to_string(variant));
            const std::uint64_t recorded =
                internals(*renderer).strategy()->report().bundlesRecorded;
            ASSERT_TRUE(renderer->selectVariant(variantOf(variant)).ok());
            EXPECT_EQ(renderer->variant(), variantOf(variant));
            renderer->renderFrame(test::frontCamera());
            auto image = renderer->readImage();
            ASSERT_TRUE(image.ok()) << image.error().message;
            if (drawsMaterials(choice.kind)) {
                const test::Rgba left = pixelOf(*image, test::kLeftQuadCenter);
                const test::Rgba right = pixelOf(*image, test::kRightQuadCenter);
                const test::Rgba expected = encode(test::kLeftQuadColors[std::size_t(variant + 1)]);
                EXPECT_LE(test::channelDistance(left, expected), 1)
                    << test::describe(left) << ", expected " << test::describe(expected);
                EXPECT_LE(test::channelDistance(right, encode(test::kRightQuadColor)), 1)
                    << test::describe(right);
            } else if (!first) {
                first = std::move(*image);
            } else {
                EXPECT_EQ(test::differingPixels(*image, *first), 0u);
            }
            // Nothing uploaded again, whatever the strategy.
            EXPECT_EQ(internals(*renderer).gpuScene(), gpuScene);
            EXPECT_EQ(internals(*renderer).sceneUploads(), 1u);
            EXPECT_EQ(internals(*renderer).uploadedBytes(), uploaded);
            // Bundles record again after a switch, and only then.
            if (renderer->bundled()) {
                if (variant != selected || recorded == 0) {
                    EXPECT_GT(internals(*renderer).strategy()->report().bundlesRecorded, recorded);
                } else {
                    EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, recorded);
                }
            }
            selected = variant;
        }
        EXPECT_TRUE(context->checkNoErrors("variants").ok());
    }
}

TEST(MaterialVariantsRenderTest, TheSelectionSurvivesASwitchOfStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = loadQuads();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Naive).ok());
    ASSERT_TRUE(renderer->selectVariant(scene::findVariant(scene, "blue paint")).ok());
    for (StrategyKind kind : {StrategyKind::Bundles, StrategyKind::GpuCullingBundles}) {
        SCOPED_TRACE(strategyName(kind));
        ASSERT_TRUE(renderer->setStrategy(kind).ok());
        renderer->renderFrame(test::frontCamera());
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        EXPECT_LE(test::channelDistance(pixelOf(*image, test::kLeftQuadCenter),
                                        encode(test::kLeftQuadColors[2])),
                  1);
    }
    EXPECT_EQ(internals(*renderer).sceneUploads(), 1u);
    // A new scene starts from the default materials.
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    EXPECT_EQ(renderer->variant(), std::nullopt);
}

TEST(MaterialVariantsRenderTest, AVariantThatDoesNotExistIsAnError) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = loadQuads();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    const auto unprepared = renderer->selectVariant(scene::VariantId(0u));
    ASSERT_FALSE(unprepared.ok());
    EXPECT_EQ(unprepared.error().code, ErrorCode::InvalidArgument);
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    const auto missing = renderer->selectVariant(scene::VariantId(4u));
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(missing.error().message,
              "Material variant 4 does not exist (the scene has 4 variants).");
    EXPECT_EQ(renderer->variant(), std::nullopt);
}

// The Khronos sample MaterialsVariantsShoe (three variants of one shoe), when ../shared/models
// has it: each variant draws a picture of its own from the one upload.
TEST(MaterialVariantsRenderTest, TheKhronosShoeDrawsEachVariant) {
    const auto models = test::sharedModelsDir();
    std::optional<std::filesystem::path> shoe;
    for (const char* file : {"MaterialsVariantsShoe/glTF-Binary/MaterialsVariantsShoe.glb",
                             "MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf"}) {
        if (models && std::filesystem::exists(*models / file)) {
            shoe = *models / file;
            break;
        }
    }
    if (!shoe) {
        GTEST_SKIP() << "MaterialsVariantsShoe is not in ../shared/models";
    }
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadScene(*shoe);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_GE(scene->variants.size(), 2u);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(*scene, StrategyKind::Bundles).ok());
    const std::uint64_t uploaded = internals(*renderer).uploadedBytes();
    const Camera camera = Camera::framing(scene->bounds, 1.0f);
    std::vector<image::ImageRgba8> images;
    for (std::size_t v = 0; v < scene->variants.size(); ++v) {
        SCOPED_TRACE(scene->variants[v]);
        ASSERT_TRUE(renderer->selectVariant(scene::VariantId(v)).ok());
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        for (const image::ImageRgba8& other : images) {
            EXPECT_GT(test::differingPixels(*image, other, 2), 50u);
        }
        images.push_back(std::move(*image));
    }
    EXPECT_EQ(internals(*renderer).sceneUploads(), 1u);
    EXPECT_EQ(internals(*renderer).uploadedBytes(), uploaded);
    EXPECT_TRUE(context->checkNoErrors("shoe").ok());
}

}  // namespace
}  // namespace encore::render
