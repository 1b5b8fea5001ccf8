// The GPU scene is built once per prepared scene and every strategy records from it: switching
// strategy uploads nothing again, and edits made through it survive the switch.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "render/GpuScene.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

scene::SceneData texturedScene() {
    scene::GeneratorOptions generator;
    generator.objectCount = 24;
    generator.meshCount = 3;
    generator.materialCount = 3;
    generator.textures = true;
    return test::generatedScene(generator);
}

TEST(GpuSceneTest, SwitchingThroughEveryStrategyUploadsNothingAgain) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = texturedScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(48, 48));
    ASSERT_TRUE(renderer.ok());
    EXPECT_EQ(internals(*renderer).sceneUploads(), 0u);
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Naive).ok());
    const GpuScene* gpuScene = internals(*renderer).gpuScene();
    ASSERT_NE(gpuScene, nullptr);
    EXPECT_EQ(internals(*renderer).sceneUploads(), 1u);
    const std::uint64_t uploaded = internals(*renderer).uploadedBytes();
    // Geometry and the textures' first levels, at least.
    EXPECT_GT(gpuScene->geometry().uploadedBytes(), 0u);
    EXPECT_GT(gpuScene->materials().uploadedBytes(), 0u);
    EXPECT_EQ(uploaded, gpuScene->uploadedBytes());

    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    for (const StrategyChoice& choice : test::everyStrategyChoice()) {
        SCOPED_TRACE(std::string(strategyName(choice.kind)) + (choice.bundle ? "+bundle" : ""));
        auto switched = renderer->setStrategy(choice.kind, choice.bundle);
        ASSERT_TRUE(switched.ok()) << switched.error().message;
        EXPECT_EQ(internals(*renderer).strategy()->kind(),
                  choice.bundle ? bundledKind(choice.kind).value_or(choice.kind) : choice.kind);
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok()) << image.error().message;
        EXPECT_GT(test::coveredFraction(*image, test::pixelAt(*image, 0, 0)), 0.05);
        EXPECT_EQ(internals(*renderer).gpuScene(), gpuScene);
        EXPECT_EQ(internals(*renderer).sceneUploads(), 1u);
        EXPECT_EQ(internals(*renderer).uploadedBytes(), uploaded);
    }

    // A new scene is a new upload; the bytes add up.
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    EXPECT_EQ(internals(*renderer).sceneUploads(), 2u);
    EXPECT_EQ(internals(*renderer).uploadedBytes(), 2 * uploaded);
}

// The frame a fresh renderer draws of `scene` with `kind`, for comparison.
image::ImageRgba8 freshImage(const scene::SceneData& scene,
                             StrategyKind kind,
                             const Camera& camera) {
    auto renderer = Renderer::create(*test::vulkanContext(), test::pixelTestOptions(48, 48));
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(scene, kind).ok());
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

TEST(GpuSceneTest, EditsSurviveASwitchOfStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions generator;
    generator.objectCount = 6;
    generator.meshCount = 2;
    generator.materialCount = 1;
    const scene::SceneData scene = test::generatedScene(generator);
    const Camera camera = Camera::framing(scene.bounds, 1.0f);

    // The same edits made to the scene data before preparing: what the edited frame must be.
    scene::SceneData edited = scene;
    edited.materials[0].baseColorFactor = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    glm::mat4 moved = edited.instances[0].world;
    moved[3] += glm::vec4(0.0f, 0.5f, 0.0f, 0.0f);
    edited.instances[0].world = moved;
    edited.instances[0].normalMatrix = scene::normalMatrixOf(moved);

    auto renderer = Renderer::create(*context, test::pixelTestOptions(48, 48));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    ASSERT_TRUE(renderer->updateMaterial(scene::MaterialId{0u}, edited.materials[0]).ok());
    ASSERT_TRUE(renderer->updateInstance(0, moved).ok());
    for (StrategyKind kind :
         {StrategyKind::Materials, StrategyKind::GpuCullingBundles, StrategyKind::Bundles}) {
        SCOPED_TRACE(strategyName(kind));
        ASSERT_TRUE(renderer->setStrategy(kind).ok());
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        EXPECT_EQ(test::differingPixels(*image, freshImage(edited, kind, camera)), 0u);
        EXPECT_GT(test::differingPixels(*image, freshImage(scene, kind, camera)), 0u);
    }
    // Strategies with transforms of their own (per-node uniforms) start from the moved one.
    ASSERT_TRUE(renderer->setStrategy(StrategyKind::Naive).ok());
    renderer->renderFrame(camera);
    auto naive = renderer->readImage();
    ASSERT_TRUE(naive.ok());
    EXPECT_EQ(test::differingPixels(*naive, freshImage(edited, StrategyKind::Naive, camera)), 0u);
}

TEST(GpuSceneTest, AReplacedImageRegroupsTheDrawsOfEveryLaterStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions generator;
    generator.objectCount = 4;
    generator.meshCount = 1;
    generator.materialCount = 1;
    const scene::SceneData scene = test::generatedScene(generator);  // No textures.
    const Camera camera = Camera::framing(scene.bounds, 1.0f);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(48, 48));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Naive).ok());
    const std::uint64_t generation = internals(*renderer).gpuScene()->generation();
    scene::Image red;
    red.width = 2;
    red.height = 2;
    red.rgba8.assign(2 * 2 * 4, 255);
    for (std::size_t i = 0; i < red.rgba8.size(); i += 4) {
        red.rgba8[i + 1] = red.rgba8[i + 2] = 0;
    }
    // Naive draws no materials, yet the GPU scene takes the edit for the strategies that do.
    ASSERT_TRUE(renderer->replaceBaseColorImage(scene::MaterialId{0u}, red).ok());
    EXPECT_GT(internals(*renderer).gpuScene()->generation(), generation);
    EXPECT_TRUE(internals(*renderer).gpuScene()->materials().textured(scene::MaterialId{0u}));
    for (StrategyKind kind : {StrategyKind::Materials, StrategyKind::Bundles}) {
        SCOPED_TRACE(strategyName(kind));
        ASSERT_TRUE(renderer->setStrategy(kind).ok());
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        ASSERT_TRUE(image.ok());
        // As if the image had been replaced under this strategy, and unlike the original.
        auto direct = Renderer::create(*context, test::pixelTestOptions(48, 48));
        ASSERT_TRUE(direct.ok());
        ASSERT_TRUE(direct->prepare(scene, kind).ok());
        ASSERT_TRUE(direct->replaceBaseColorImage(scene::MaterialId{0u}, red).ok());
        direct->renderFrame(camera);
        auto expected = direct->readImage();
        ASSERT_TRUE(expected.ok());
        EXPECT_EQ(test::differingPixels(*image, *expected), 0u);
        EXPECT_GT(test::differingPixels(*image, freshImage(scene, kind, camera)), 20u);
    }
    EXPECT_TRUE(context->checkNoErrors("replaced image").ok());
}

}  // namespace
}  // namespace encore::render
