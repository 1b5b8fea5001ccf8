// Load-time mesh optimisation changes the order of triangles and vertices, never what is drawn:
// scenes loaded with LoadOptions::optimizeMeshes on and off render to identical pixels, with no
// tolerance. Rasterisation gives every pixel to one triangle of a shared edge whatever the order,
// depth-tested opaque triangles reach the same result in any order unless two of them tie in
// depth over a pixel, and blended primitives keep their triangle order (MeshOptimizer.h).

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/render/Renderer.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 160;

scene::LoadOptions loadOptions(bool optimise,
                               scene::VertexCacheOrder order = scene::VertexCacheOrder::Thorough) {
    scene::LoadOptions options;
    options.optimizeMeshes = optimise;
    options.buildLevelsOfDetail = optimise;
    options.vertexCacheOrder = order;
    return options;
}

// Renders `scene` shaded (every material input, image-based lighting) with `kind`, framed, at
// `timeSeconds` into its first animation (skinning and morphing deform the meshes).
image::ImageRgba8 render(gpu::Context& context,
                         const scene::SceneData& scene,
                         StrategyKind kind,
                         float timeSeconds) {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.toneMapping.toneMapping = ToneMapping::PbrNeutral;
    auto renderer = Renderer::create(context, options);
    EXPECT_TRUE(renderer.ok()) << renderer.error().message;
    if (!renderer.ok()) {
        return {};
    }
    auto prepared = renderer->prepare(scene, kind);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    renderer->renderFrame(Camera::framing(scene.bounds, renderer->target().aspect()), timeSeconds);
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    EXPECT_TRUE(context.checkNoErrors("mesh optimiser render").ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

void expectSamePixels(gpu::Context& context,
                      const scene::SceneData& plain,
                      const scene::SceneData& optimised,
                      float timeSeconds = 0.0f) {
    for (StrategyKind kind :
         {StrategyKind::Naive, StrategyKind::Materials, StrategyKind::GpuCulling}) {
        SCOPED_TRACE(strategyName(kind));
        const image::ImageRgba8 before = render(context, plain, kind, timeSeconds);
        const image::ImageRgba8 after = render(context, optimised, kind, timeSeconds);
        ASSERT_EQ(before.width, after.width);
        EXPECT_GT(test::coveredFraction(before, test::pixelAt(before, 0, 0)), 0.002);
        EXPECT_EQ(test::differingPixels(before, after), 0u);
    }
}

TEST(MeshOptimizerRenderTest, GeneratedSceneDrawsTheSamePixels) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions generator;
    generator.objectCount = 27;
    generator.meshCount = 8;
    generator.tessellation = 24;
    generator.textures = true;
    auto glb = scene::generateSceneGlb(generator);
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto plain = scene::loadSceneFromMemory(*glb, {}, "generated.glb", loadOptions(false));
    auto optimised = scene::loadSceneFromMemory(*glb, {}, "generated.glb", loadOptions(true));
    ASSERT_TRUE(plain.ok()) << plain.error().message;
    ASSERT_TRUE(optimised.ok()) << optimised.error().message;
    std::size_t levels = 0;
    for (const scene::Mesh& mesh : optimised->meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            levels += primitive.levels.size();
        }
    }
    EXPECT_GT(levels, 0u);
    expectSamePixels(*context, *plain, *optimised);
    // The fast FIFO order (encore batch) draws the same too.
    auto fast = scene::loadSceneFromMemory(*glb, {}, "generated.glb",
                                           loadOptions(true, scene::VertexCacheOrder::Fast));
    ASSERT_TRUE(fast.ok()) << fast.error().message;
    expectSamePixels(*context, *plain, *fast);
}

TEST(MeshOptimizerRenderTest, SharedModelsDrawTheSamePixels) {
    const auto models = test::sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "../shared/models is absent beside the clone";
    }
    ENCORE_REQUIRE_VULKAN(context);
    // Textured, skinned (BrainStem, Fox), morphed (AnimatedMorphCube), blended
    // (AlphaBlendModeTest), quantized (Duck) and multi-primitive (CesiumMilkTruck) models.
    const char* files[] = {"BoxTextured/glTF/BoxTextured.gltf",
                           "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb",
                           "Fox/glTF-Binary/Fox.glb",
                           "BrainStem/glTF-Binary/BrainStem.glb",
                           "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
                           "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb",
                           "Duck/glTF-Quantized/Duck.gltf"};
    for (const char* file : files) {
        const std::filesystem::path path = *models / file;
        if (!std::filesystem::exists(path)) {
            continue;
        }
        SCOPED_TRACE(file);
        auto plain = scene::loadScene(path, loadOptions(false));
        auto optimised = scene::loadScene(path, loadOptions(true));
        ASSERT_TRUE(plain.ok()) << plain.error().message;
        ASSERT_TRUE(optimised.ok()) << optimised.error().message;
        expectSamePixels(*context, *plain, *optimised, /*timeSeconds=*/0.5f);
    }
}

}  // namespace
}  // namespace encore::render
