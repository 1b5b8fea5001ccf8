// Per-frame call counts of every strategy against what the glTF structure implies, on every
// sample model and on a generated scene; plus the call order each strategy promises.

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "core/FileIO.h"
#include "encore/render/Renderer.h"
#include "render/GpuScene.h"
#include "render/renderer/CreateStrategy.h"
#include "render/renderer/RendererCore.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

using test::ModelVariant;

// What the scene's structure says each strategy must do.
struct Structure {
    std::uint64_t instances = 0;           // Mesh nodes (and GPU-instancing copies).
    std::uint64_t nodePrimitiveDraws = 0;  // Sum over instances of their mesh's primitives.
    std::uint64_t nodeIndexedDraws = 0;
    std::uint64_t drawnPrimitives = 0;  // Primitives of meshes with at least one instance.
    std::uint64_t drawnIndexed = 0;
    std::uint64_t allPrimitives = 0;  // Of every mesh, instanced or not.
    // Animation (skinned or morphed primitives): the animation bind group is set before each
    // of their draws; skinned ones also bind JOINTS_n/WEIGHTS_n.
    std::uint64_t animatedNodeDraws = 0;  // (instance, animated primitive) pairs.
    std::uint64_t animatedDrawnPrimitives = 0;
    std::uint64_t naiveSlots = 0;  // One per attribute bound, per (node, primitive).
};

// Vertex buffer slots of one frame per model, written out (taken once from `encore stats` and
// checked against the models' accessors) rather than derived from VertexBindings.cpp's rule, so
// that a change of the rule fails here. Position and normal share a slot where they are
// interleaved in one bufferView; skinned primitives also bind JOINTS_n and WEIGHTS_n.
struct VertexSlots {
    std::uint64_t layouts = 0;        // Every (node, primitive) binds its slots.
    std::uint64_t pipelineCache = 0;  // Each drawn primitive binds its slots once.
};

const std::map<std::string, VertexSlots>& sharedModelSlots() {
    static const std::map<std::string, VertexSlots> slots = {
        {"2CylinderEngine_glTF", {230, 68}},
        {"2CylinderEngine_glTF_Binary", {230, 68}},
        {"2CylinderEngine_glTF_Draco", {230, 68}},
        {"AlphaBlendModeTest_glTF", {18, 18}},
        {"AlphaBlendModeTest_glTF_Binary", {18, 18}},
        {"AnimatedMorphCube_glTF", {2, 2}},
        {"AnimatedMorphCube_glTF_Binary", {2, 2}},
        {"AnimatedMorphCube_glTF_Quantized", {2, 2}},
        {"Avocado_glTF", {2, 2}},
        {"Box_glTF", {2, 2}},
        {"Box_glTF_Binary", {2, 2}},
        {"Box_glTF_Draco", {2, 2}},
        {"Box_glTF_Embedded", {2, 2}},
        {"BoxInterleaved_glTF", {2, 2}},
        {"BoxInterleaved_glTF_Binary", {2, 2}},
        {"BoxInterleaved_glTF_Embedded", {2, 2}},
        {"BoxTextured_glTF", {2, 2}},
        {"BoxTextured_glTF_Binary", {2, 2}},
        {"BoxTextured_glTF_Embedded", {2, 2}},
        {"BoxVertexColors_glTF", {2, 2}},
        {"BoxVertexColors_glTF_Binary", {2, 2}},
        {"BrainStem_glTF", {236, 236}},
        {"BrainStem_glTF_Binary", {236, 236}},
        {"BrainStem_glTF_Draco", {236, 236}},
        {"Buggy_glTF_Draco", {472, 296}},
        {"CesiumMilkTruck_glTF", {10, 8}},
        {"CesiumMilkTruck_glTF_Binary", {10, 8}},
        {"CesiumMilkTruck_glTF_Draco", {10, 8}},
        {"Duck_glTF", {2, 2}},
        {"Duck_glTF_Binary", {2, 2}},
        {"Duck_glTF_Draco", {2, 2}},
        {"Duck_glTF_Embedded", {2, 2}},
        {"Duck_glTF_Quantized", {2, 2}},
        {"FlightHelmet_glTF", {12, 12}},
        {"Fox_glTF", {4, 4}},
        {"Fox_glTF_Binary", {4, 4}},
        {"GearboxAssy_glTF_Draco", {190, 84}},
        {"MeshoptPirate_glTF_Meshopt", {2, 2}},
        {"MeshPrimitiveModes_glTF", {14, 14}},
        {"MeshPrimitiveModes_glTF_Embedded", {14, 14}},
        {"MetalRoughSpheresNoTextures_glTF", {246, 246}},
        {"MetalRoughSpheresNoTextures_glTF_Binary", {246, 246}},
        {"MultiUVTest_glTF", {2, 2}},
        {"MultiUVTest_glTF_Binary", {2, 2}},
        {"NormalTangentTest_glTF", {2, 2}},
        {"NormalTangentTest_glTF_Binary", {2, 2}},
        {"OrientationTest_glTF", {26, 26}},
        {"OrientationTest_glTF_Binary", {26, 26}},
        {"ReciprocatingSaw_glTF", {226, 130}},
        {"ReciprocatingSaw_glTF_Binary", {226, 130}},
        {"ReciprocatingSaw_glTF_Draco", {226, 130}},
        {"SimpleInstancing_glTF", {250, 2}},
        {"SimpleInstancing_glTF_Binary", {250, 2}},
        {"SimpleMeshes_glTF", {4, 2}},
        {"SimpleMeshes_glTF_Embedded", {4, 2}},
        {"SimpleSparseAccessor_glTF", {2, 2}},
        {"SimpleSparseAccessor_glTF_Embedded", {2, 2}},
        {"TextureCoordinateTest_glTF", {10, 10}},
        {"TextureCoordinateTest_glTF_Binary", {10, 10}},
        {"TextureSettingsTest_glTF", {20, 20}},
        {"TextureSettingsTest_glTF_Binary", {20, 20}},
        {"TextureTransformTest_glTF", {24, 18}},
        {"Triangle_glTF", {2, 2}},
        {"Triangle_glTF_Embedded", {2, 2}},
        {"TriangleWithoutIndices_glTF", {2, 2}},
        {"TriangleWithoutIndices_glTF_Embedded", {2, 2}},
        {"VertexColorTest_glTF", {4, 4}},
        {"VertexColorTest_glTF_Binary", {4, 4}},
    };
    return slots;
}

// The skinning attributes a primitive binds: none unless a node with a skin draws its mesh.
std::vector<scene::Semantic> skinSemantics(const scene::Primitive& primitive, bool meshSkinned) {
    using S = scene::Semantic;
    if (!meshSkinned || !primitive.attribute(S::Joints0) || !primitive.attribute(S::Weights0)) {
        return {};
    }
    if (primitive.attribute(S::Joints1) && primitive.attribute(S::Weights1)) {
        return {S::Joints0, S::Weights0, S::Joints1, S::Weights1};
    }
    return {S::Joints0, S::Weights0};
}

Structure structureOf(const scene::SceneData& scene) {
    Structure s;
    std::vector<std::uint64_t> instancesOfMesh(scene.meshes.size(), 0);
    std::vector<bool> meshSkinned(scene.meshes.size(), false);
    for (const auto& instance : scene.instances) {
        ++instancesOfMesh[instance.mesh.index()];
        if (scene.nodes[instance.node.index()].skin) {
            meshSkinned[instance.mesh.index()] = true;
        }
    }
    s.instances = scene.instances.size();
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        for (const auto& primitive : scene.meshes[mesh].primitives) {
            const auto skin = skinSemantics(primitive, meshSkinned[mesh]);
            std::vector<scene::Semantic> bound = {scene::Semantic::Position,
                                                  scene::Semantic::Normal};
            bound.insert(bound.end(), skin.begin(), skin.end());
            const bool animated = !skin.empty() || !primitive.targets.empty();
            s.animatedNodeDraws += animated ? instancesOfMesh[mesh] : 0;
            s.naiveSlots += bound.size() * instancesOfMesh[mesh];
            const bool indexed = primitive.indices.has_value();
            ++s.allPrimitives;
            s.nodePrimitiveDraws += instancesOfMesh[mesh];
            s.nodeIndexedDraws += indexed ? instancesOfMesh[mesh] : 0;
            if (instancesOfMesh[mesh] > 0) {
                ++s.drawnPrimitives;
                s.animatedDrawnPrimitives += animated;
                s.drawnIndexed += indexed;
            }
        }
    }
    return s;
}

struct Frame {
    DrawCounters counters;
    std::uint64_t pipelinesCreated = 0;
    std::vector<RecordedCall> trace;
};

Frame renderWith(Renderer& renderer, const scene::SceneData& scene, StrategyKind kind) {
    Frame frame;
    auto prepared = renderer.prepare(scene, kind);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    frame.pipelinesCreated = internals(renderer).setup().pipelinesCreated;
    frame.counters = internals(renderer)
                         .renderFrame(Camera::framing(scene.bounds, 1.0f), 0.0f, &frame.trace)
                         .counters;
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return frame;
}

std::uint64_t calls(const Frame& frame, RecordedCall::Kind kind, std::uint32_t index) {
    std::uint64_t count = 0;
    for (const auto& call : frame.trace) {
        count += call.kind == kind && call.index == index;
    }
    return count;
}

// Each pipeline is set once: the loops are grouped by pipeline.
void expectEachPipelineSetOnce(const Frame& frame) {
    std::set<const void*> seen;
    for (const auto& call : frame.trace) {
        if (call.kind == RecordedCall::Kind::SetPipeline) {
            EXPECT_TRUE(seen.insert(call.object).second) << "a pipeline was set twice";
        }
    }
}

void checkCounts(const scene::SceneData& scene, const VertexSlots& slots) {
    ENCORE_REQUIRE_VULKAN(context);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(64, 64));
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    const Structure s = structureOf(scene);

    const Frame naive = renderWith(*renderer, scene, StrategyKind::Naive);
    EXPECT_EQ(naive.pipelinesCreated, s.allPrimitives);
    EXPECT_EQ(naive.counters.setPipeline, s.nodePrimitiveDraws);  // Per (node, primitive).
    EXPECT_EQ(naive.counters.drawCalls(), s.nodePrimitiveDraws);
    // Frame + one per node (+ the animation group per animated draw).
    EXPECT_EQ(naive.counters.setBindGroup, 1 + s.instances + s.animatedNodeDraws);
    EXPECT_EQ(naive.counters.setVertexBuffer, s.naiveSlots);
    EXPECT_EQ(naive.counters.setIndexBuffer, s.nodeIndexedDraws);
    EXPECT_EQ(naive.counters.instances, s.nodePrimitiveDraws);

    const Frame layouts = renderWith(*renderer, scene, StrategyKind::Layouts);
    EXPECT_EQ(layouts.counters.setPipeline, s.nodePrimitiveDraws);
    EXPECT_EQ(layouts.counters.setVertexBuffer, slots.layouts);
    EXPECT_EQ(layouts.counters.drawCalls(), s.nodePrimitiveDraws);

    const Frame cache = renderWith(*renderer, scene, StrategyKind::PipelineCache);
    EXPECT_LE(cache.pipelinesCreated, s.drawnPrimitives);
    EXPECT_EQ(cache.counters.setPipeline, cache.pipelinesCreated);  // Once per distinct key.
    EXPECT_EQ(cache.counters.drawCalls(), s.nodePrimitiveDraws);
    EXPECT_EQ(cache.counters.setBindGroup, 1 + s.nodePrimitiveDraws + s.animatedNodeDraws);
    EXPECT_EQ(cache.counters.setVertexBuffer, slots.pipelineCache);  // Once per primitive.
    EXPECT_EQ(cache.counters.setIndexBuffer, s.drawnIndexed);
    expectEachPipelineSetOnce(cache);

    const Frame instancing = renderWith(*renderer, scene, StrategyKind::Instancing);
    EXPECT_EQ(instancing.counters.drawCalls(), s.drawnPrimitives);  // One per primitive.
    // Frame and the instance buffer, once (+ the animation group per animated draw).
    EXPECT_EQ(instancing.counters.setBindGroup, 2u + s.animatedDrawnPrimitives);
    EXPECT_EQ(calls(instancing, RecordedCall::Kind::SetBindGroup, 1), 1u);
    EXPECT_EQ(instancing.counters.instances, s.nodePrimitiveDraws);
    EXPECT_EQ(instancing.counters.setPipeline, instancing.pipelinesCreated);
    EXPECT_EQ(instancing.counters.triangles, naive.counters.triangles);
    expectEachPipelineSetOnce(instancing);

    const Frame materials = renderWith(*renderer, scene, StrategyKind::Materials);
    EXPECT_EQ(materials.counters.triangles, naive.counters.triangles);
    EXPECT_EQ(calls(materials, RecordedCall::Kind::SetBindGroup, 1), 1u);
    // Opaque geometry: each material bind group set at most once per pipeline that uses it.
    std::set<std::pair<const void*, const void*>> materialPerPipeline;
    const void* pipeline = nullptr;
    bool blendedPart = false;
    std::set<const void*> opaquePipelines;
    for (const auto& call : materials.trace) {
        if (call.kind == RecordedCall::Kind::SetPipeline) {
            // Blended draws come last and may return to a pipeline (back-to-front order).
            blendedPart = blendedPart || opaquePipelines.contains(call.object);
            opaquePipelines.insert(call.object);
            pipeline = call.object;
        } else if (call.kind == RecordedCall::Kind::SetBindGroup && call.index == 2 &&
                   !blendedPart) {
            EXPECT_TRUE(materialPerPipeline.insert({pipeline, call.object}).second)
                << "a material was set twice under one pipeline";
        }
    }
    std::set<scene::MaterialId> usedMaterials;
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        for (const auto& primitive : scene.meshes[mesh].primitives) {
            usedMaterials.insert(primitive.material);
        }
    }
    EXPECT_GE(calls(materials, RecordedCall::Kind::SetBindGroup, 2),
              s.drawnPrimitives > 0 ? 1u : 0u);
    EXPECT_TRUE(context->checkNoErrors("counting").ok());
}

class StrategyCountsTest : public ::testing::TestWithParam<ModelVariant> {};

TEST_P(StrategyCountsTest, CountsFollowTheGltfStructure) {
    const ModelVariant& model = GetParam();
    if (model.path.empty()) {
        GTEST_SKIP() << "../shared/models is absent beside the clone: no sample model counted";
    }
    const auto slots = sharedModelSlots().find(model.testName());
    ASSERT_NE(slots, sharedModelSlots().end())
        << model.testName() << " has no vertex slot counts written in sharedModelSlots().";
    auto scene = scene::loadScene(model.path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    checkCounts(*scene, slots->second);
}

std::vector<ModelVariant> variants() {
    auto all = test::sharedModelVariants();
    if (all.empty()) {
        all.push_back({"none", "none", ""});
    }
    return all;
}

INSTANTIATE_TEST_SUITE_P(SharedModels,
                         StrategyCountsTest,
                         ::testing::ValuesIn(variants()),
                         [](const auto& info) { return info.param.testName(); });

// A generated scene of `objects` instances of `meshes` meshes with `materials` materials.
Result<scene::SceneData> generatedScene(std::uint32_t objects,
                                        std::uint32_t meshes,
                                        std::uint32_t materials,
                                        const std::string& name) {
    scene::GeneratorOptions options;
    options.objectCount = objects;
    options.meshCount = meshes;
    options.materialCount = materials;
    auto glb = scene::generateSceneGlb(options);
    if (!glb) {
        return glb.error();
    }
    return scene::loadSceneFromMemory(*glb, {}, name);
}

TEST(StrategyCountsGeneratedTest, ManyInstancesOfFewMeshes) {
    auto scene = generatedScene(300, 7, 3, "generated.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    // Position and normal in two slots: 2 per object, 2 per mesh.
    checkCounts(*scene, {600, 14});

    // The generator's shapes share one vertex layout: instancing draws each mesh once.
    ENCORE_REQUIRE_VULKAN(context);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(64, 64));
    ASSERT_TRUE(renderer.ok());
    const Frame instancing = renderWith(*renderer, *scene, StrategyKind::Instancing);
    EXPECT_EQ(instancing.counters.drawCalls(), 7u);
    EXPECT_EQ(instancing.counters.setPipeline, 1u);
    EXPECT_EQ(instancing.counters.instances, 300u);
    const Frame materials = renderWith(*renderer, *scene, StrategyKind::Materials);
    EXPECT_EQ(calls(materials, RecordedCall::Kind::SetBindGroup, 2), 3u);  // One per material.
}

// RendererOptions::keepPipelines: a renderer that prepares scene after scene (encore batch)
// creates each distinct pipeline once, and draws the same picture with it.
TEST(StrategyCountsGeneratedTest, KeptPipelinesAreCreatedOncePerRenderer) {
    auto first = generatedScene(20, 3, 2, "first.glb");
    auto second = generatedScene(20, 3, 2, "second.glb");
    ASSERT_TRUE(first.ok() && second.ok());
    ENCORE_REQUIRE_VULKAN(context);
    RendererOptions keeping = test::pixelTestOptions(64, 64);
    keeping.keepPipelines = true;
    auto renderer = Renderer::create(*context, keeping);
    ASSERT_TRUE(renderer.ok());
    const Frame once = renderWith(*renderer, *first, StrategyKind::Bundles);
    EXPECT_GT(once.pipelinesCreated, 0u);
    const image::ImageRgba8 firstImage = *renderer->readImage();
    const Frame again = renderWith(*renderer, *second, StrategyKind::Bundles);
    EXPECT_EQ(again.pipelinesCreated, 0u);
    EXPECT_EQ(test::differingPixels(*renderer->readImage(), firstImage), 0u);

    // Without it (the default) each prepare creates its strategy's pipelines.
    auto plain = Renderer::create(*context, test::pixelTestOptions(64, 64));
    ASSERT_TRUE(plain.ok());
    renderWith(*plain, *first, StrategyKind::Bundles);
    EXPECT_EQ(renderWith(*plain, *second, StrategyKind::Bundles).pipelinesCreated,
              once.pipelinesCreated);
    EXPECT_TRUE(context->checkNoErrors("kept pipelines").ok());
}

// The case study's published Buggy figures: 236 -> 1 setPipeline, 191 -> 237 setBindGroup,
// 708 -> 444 vertex + index buffer sets, with pipeline caching.
TEST(StrategyCountsGeneratedTest, BuggyMatchesTheCaseStudy) {
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        GTEST_SKIP() << "../shared/models is absent beside the clone";
    }
    auto scene = scene::loadScene(*dir / "Buggy/glTF-Draco/Buggy.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ENCORE_REQUIRE_VULKAN(context);
    auto renderer = Renderer::create(*context, test::pixelTestOptions(64, 64));
    ASSERT_TRUE(renderer.ok());
    const Frame layouts = renderWith(*renderer, *scene, StrategyKind::Layouts);
    const Frame cache = renderWith(*renderer, *scene, StrategyKind::PipelineCache);
    EXPECT_EQ(layouts.counters.setPipeline, 236u);
    EXPECT_EQ(cache.counters.setPipeline, 1u);
    EXPECT_EQ(layouts.counters.setBindGroup, 191u);
    EXPECT_EQ(cache.counters.setBindGroup, 237u);
    EXPECT_EQ(layouts.counters.setVertexBuffer + layouts.counters.setIndexBuffer, 708u);
    EXPECT_EQ(cache.counters.setVertexBuffer + cache.counters.setIndexBuffer, 444u);
}

}  // namespace
}  // namespace encore::render

namespace encore::render {
namespace {

// Drivers that map memory per object (lavapipe) crash past the kernel's mapping limit: the
// per-node strategies refuse such scenes with an error naming the fix instead.
TEST(StrategyLimitsTest, PerNodeStrategiesRefuseScenesBeyondTheMappingBudget) {
    ENCORE_REQUIRE_VULKAN(context);
    scene::GeneratorOptions options;
    options.objectCount = 50;
    auto glb = scene::generateSceneGlb(options);
    ASSERT_TRUE(glb.ok());
    auto scene = scene::loadSceneFromMemory(*glb, {}, "fifty.glb");
    ASSERT_TRUE(scene.ok());
    auto renderer = Renderer::create(*context, test::pixelTestOptions(32, 32));
    ASSERT_TRUE(renderer.ok());
    RenderSetup tight = internals(*renderer).setup();
    tight.mappingBudget = 60;  // Room for 30 nodes at two mappings each.
    auto gpuScene = GpuScene::create(tight, *scene);
    ASSERT_TRUE(gpuScene.ok());
    for (StrategyKind kind :
         {StrategyKind::Naive, StrategyKind::Layouts, StrategyKind::PipelineCache}) {
        auto strategy = createStrategy(kind);
        auto prepared = strategy->prepare(tight, **gpuScene);
        ASSERT_FALSE(prepared.ok()) << strategyName(kind);
        EXPECT_EQ(prepared.error().code, ErrorCode::Unsupported);
        EXPECT_NE(prepared.error().message.find("vm.max_map_count"), std::string::npos);
        EXPECT_NE(prepared.error().message.find("50 mesh nodes"), std::string::npos);
    }
    // Instancing needs no per-node objects.
    auto instancing = createStrategy(StrategyKind::Instancing);
    EXPECT_TRUE(instancing->prepare(tight, **gpuScene).ok());
    EXPECT_TRUE(context->checkNoErrors("limits").ok());
}

}  // namespace
}  // namespace encore::render
