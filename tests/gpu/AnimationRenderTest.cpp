// Playing animations in every strategy: GPU skinning and morph targets from CPU-evaluated
// joint matrices and weights (render::AnimationBuffers), node animation through the strategies'
// instance buffers, bundles that stay recorded while the animation plays, and the Khronos
// sample models at two times.

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/render/Renderer.h"
#include "render/InstanceBuffer.h"
#include "render/culling/GpuCuller.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

using test::frontCamera;

// A red quad (0.8 wide) centred at `center`, as one primitive's attribute map.
test::GltfBuilder::PrimitiveDesc quad(test::GltfBuilder& builder, glm::vec3 center) {
    test::GltfBuilder::PrimitiveDesc primitive;
    const float h = 0.4f;
    primitive.attributes["POSITION"] =
        builder.addPositions({center + glm::vec3(-h, -h, 0), center + glm::vec3(h, -h, 0),
                              center + glm::vec3(h, h, 0), center + glm::vec3(-h, h, 0)});
    primitive.attributes["NORMAL"] =
        builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    primitive.material = builder.addMaterial({.baseColor = {1, 0, 0, 1}, .doubleSided = true});
    return primitive;
}

// A LINEAR animation of one node's `path`, key times 0 and 1.
void addAnimation(test::GltfBuilder& builder,
                  std::uint32_t node,
                  const std::string& path,
                  const std::vector<float>& values,
                  const std::string& type) {
    const auto times = builder.addAccessor<float>({0.0f, 1.0f}, "SCALAR", {.minMax = true});
    const auto output = builder.addAccessor<float>(values, type);
    builder.json()["animations"].push_back(
        {{"samplers", {{{"input", times}, {"output", output}, {"interpolation", "LINEAR"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}});
}

scene::SceneData load(const test::GltfBuilder& builder, const std::string& name) {
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, name);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// A quad centred at (0, 1, 0), skinned to joint 1 (a child of joint 0 at the origin), which
// turns 90 degrees about +Z between t = 0 and t = 1: the quad moves to (-1, 0, 0). The mesh's
// node is translated by `meshNodeTranslation`, which glTF says a skinned mesh ignores.
scene::SceneData skinnedScene(glm::vec3 meshNodeTranslation = {2, 0, 0}) {
    test::GltfBuilder builder;
    auto primitive = quad(builder, {0, 1, 0});
    primitive.attributes["JOINTS_0"] =
        builder.addAccessor<std::uint8_t>({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    primitive.attributes["WEIGHTS_0"] =
        builder.addAccessor<float>({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    const auto mesh = builder.addMesh(primitive);
    const auto meshNode = builder.addNode({.mesh = mesh, .translation = meshNodeTranslation});
    const auto joint1 = builder.addNode({.name = "joint1"});
    const auto joint0 = builder.addNode({.children = {joint1}, .name = "joint0"});
    builder.json()["nodes"][meshNode]["skin"] = 0;
    builder.json()["skins"] = {{{"joints", {joint0, joint1}}}};
    const float s = std::sin(glm::quarter_pi<float>());
    addAnimation(builder, joint1, "rotation", {0, 0, 0, 1, 0, 0, s, s}, "VEC4");
    builder.addScene({meshNode, joint0});
    return load(builder, "skinned.glb");
}

// A quad at the origin with one morph target moving it by (+1.5, 0, 0); its weight goes from
// 0 at t = 0 to 1 at t = 1.
scene::SceneData morphedScene() {
    test::GltfBuilder builder;
    const auto primitive = quad(builder, {0, 0, 0});
    const auto delta =
        builder.addPositions({{1.5f, 0, 0}, {1.5f, 0, 0}, {1.5f, 0, 0}, {1.5f, 0, 0}});
    const auto mesh = builder.addMesh(primitive);
    builder.json()["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", delta}}};
    builder.json()["meshes"][mesh]["weights"] = {0.0};
    const auto node = builder.addNode({.mesh = mesh});
    addAnimation(builder, node, "weights", {0.0f, 1.0f}, "SCALAR");
    builder.addScene({node});
    return load(builder, "morphed.glb");
}

struct Rendered {
    image::ImageRgba8 image;
    std::uint64_t bundlesRecorded = 0;
};

// Renders `scene` with `kind` at each of `times` (one renderer: bundles recorded once).
std::vector<image::ImageRgba8> renderAt(const scene::SceneData& scene,
                                        StrategyKind kind,
                                        const std::vector<double>& times,
                                        const Camera& camera = frontCamera(),
                                        const std::string& animation = {}) {
    gpu::Context* context = test::vulkanContext();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    EXPECT_TRUE(renderer.ok());
    auto prepared = renderer->prepare(scene, kind);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    EXPECT_TRUE(renderer->selectAnimation(animation).ok());
    std::vector<image::ImageRgba8> images;
    for (double t : times) {
        EXPECT_TRUE(renderer->setAnimationTime(t).ok());
        renderer->renderFrame(camera);
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok()) << image.error().message;
        images.push_back(image.ok() ? std::move(*image) : image::ImageRgba8{});
    }
    auto errors =
        context->checkNoErrors(std::string("animating with ") + std::string(strategyName(kind)));
    EXPECT_TRUE(errors.ok()) << errors.error().message;
    return images;
}

bool coveredAt(const image::ImageRgba8& image, const glm::vec3& point) {
    const auto [x, y] = test::pixelOf(frontCamera(), point, kSize, kSize);
    const test::Rgba background = test::pixelAt(image, 1, 1);
    return test::channelDistance(test::pixelAt(image, x, y), background) > 20;
}

bool hasMaterials(StrategyKind kind) {
    return kind >= StrategyKind::Materials;
}

// Every strategy draws the animated quad where the animation puts it, and strategies of one
// family (vertex colours, or materials) produce identical images.
void expectAnimatedEverywhere(const scene::SceneData& scene,
                              const std::vector<double>& times,
                              const std::vector<std::vector<glm::vec3>>& covered,
                              const std::vector<std::vector<glm::vec3>>& uncovered) {
    std::vector<image::ImageRgba8> unlit, materials;
    for (StrategyKind kind : allStrategies()) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        const auto images = renderAt(scene, kind, times);
        ASSERT_EQ(images.size(), times.size());
        for (std::size_t i = 0; i < times.size(); ++i) {
            SCOPED_TRACE("t = " + std::to_string(times[i]));
            for (const glm::vec3& point : covered[i]) {
                EXPECT_TRUE(coveredAt(images[i], point))
                    << "nothing drawn at (" << point.x << ", " << point.y << ")";
            }
            for (const glm::vec3& point : uncovered[i]) {
                EXPECT_FALSE(coveredAt(images[i], point))
                    << "something drawn at (" << point.x << ", " << point.y << ")";
            }
        }
        auto& reference = hasMaterials(kind) ? materials : unlit;
        if (reference.empty()) {
            reference = images;
            continue;
        }
        for (std::size_t i = 0; i < times.size(); ++i) {
            EXPECT_EQ(test::differingPixels(images[i], reference[i], 0), 0u)
                << "differs from the first strategy of its family at t = " << times[i];
        }
    }
}

TEST(AnimationRenderTest, SkinnedQuadFollowsItsJointInEveryStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = skinnedScene();
    ASSERT_EQ(scene.skins.size(), 1u);
    // t = 0: at (0, 1) (not at the mesh node's (2, 1)); t = 1: turned to (-1, 0).
    expectAnimatedEverywhere(scene, {0.0, 1.0}, {{{0, 1, 0}}, {{-1, 0, 0}}},
                             {{{2, 1, 0}, {-1, 0, 0}}, {{0, 1, 0}, {1, 0, 0}}});
}

TEST(AnimationRenderTest, MorphedQuadFollowsItsWeightInEveryStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = morphedScene();
    expectAnimatedEverywhere(scene, {0.0, 0.5, 1.0}, {{{0, 0, 0}}, {{0.75f, 0, 0}}, {{1.5f, 0, 0}}},
                             {{{1.5f, 0, 0}}, {{-0.6f, 0, 0}, {1.6f, 0, 0}}, {{0, 0, 0}}});
}

// GPU culling must not cull a skinned instance by its node's transform: here the node lies far
// outside the view, the skinned quad inside it.
TEST(AnimationRenderTest, GpuCullingKeepsSkinnedInstancesWhoseNodeIsOutOfView) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = skinnedScene({50, 0, 0});
    for (StrategyKind kind : {StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        const auto images = renderAt(scene, kind, {0.0, 1.0});
        ASSERT_EQ(images.size(), 2u);
        EXPECT_TRUE(coveredAt(images[0], {0, 1, 0}));
        EXPECT_TRUE(coveredAt(images[1], {-1, 0, 0}));
    }
}

// Three quads cross the view from x = -6 to x = +6 (the front camera sees [-3, 3]) between
// t = 0 and t = 1, each moved by a different kind of animation: a rigid node's translation
// (y = 1), a joint its vertices are skinned to (y = 0), and a morph target of +12 whose weight
// goes from 0 to 1 (y = -1). Meshes 0, 1 and 2 in that order.
scene::SceneData crossingScene() {
    test::GltfBuilder builder;
    const auto rigidMesh = builder.addMesh(quad(builder, {0, 1, 0}));
    auto skinned = quad(builder, {0, 0, 0});
    skinned.attributes["JOINTS_0"] =
        builder.addAccessor<std::uint8_t>(std::vector<std::uint8_t>(16, 0), "VEC4");
    skinned.attributes["WEIGHTS_0"] =
        builder.addAccessor<float>({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    const auto skinnedMesh = builder.addMesh(skinned);
    const auto morphedMesh = builder.addMesh(quad(builder, {-6, -1, 0}));
    const auto delta = builder.addPositions({{12, 0, 0}, {12, 0, 0}, {12, 0, 0}, {12, 0, 0}});
    builder.json()["meshes"][morphedMesh]["primitives"][0]["targets"] = {{{"POSITION", delta}}};
    builder.json()["meshes"][morphedMesh]["weights"] = {0.0};

    const auto rigid = builder.addNode({.mesh = rigidMesh});
    const auto skinnedNode = builder.addNode({.mesh = skinnedMesh});
    const auto joint = builder.addNode({.name = "joint"});
    builder.json()["nodes"][skinnedNode]["skin"] = 0;
    builder.json()["skins"] = {{{"joints", {joint}}}};
    const auto morphed = builder.addNode({.mesh = morphedMesh});
    addAnimation(builder, rigid, "translation", {-6, 0, 0, 6, 0, 0}, "VEC3");
    addAnimation(builder, joint, "translation", {-6, 0, 0, 6, 0, 0}, "VEC3");
    addAnimation(builder, morphed, "weights", {0.0f, 1.0f}, "SCALAR");
    builder.addScene({rigid, skinnedNode, joint, morphed});
    return load(builder, "crossing.glb");
}

// GPU culling follows animated geometry across the frustum edge, whether the CPU or the GPU
// evaluates the animation: out of view, the rigid and skinned quads are culled; crossing the
// edge or inside, every quad is drawn, and each frame equals `materials`' frame. The morphed
// quad's bounds grow with its weight (|weight| times the target's largest delta), so it stays
// drawn once its weight is large, out of view or not: conservative, never wrong.
TEST(AnimationRenderTest, GpuCullingFollowsAnimationAcrossTheFrustumEdge) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = crossingScene();
    ASSERT_EQ(scene.meshes.size(), 3u);
    const std::vector<double> times = {0.0, 0.25, 0.5, 0.75, 1.0};
    // Per time, per mesh (rigid, skinned, morphed): the expected visible instance count.
    const std::vector<std::vector<std::uint32_t>> expected = {
        {0, 0, 0}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {0, 0, 1}};
    const std::vector<std::uint32_t> slots = instanceSlots(scene);
    for (AnimationEvaluation evaluation : {AnimationEvaluation::Cpu, AnimationEvaluation::Gpu}) {
        SCOPED_TRACE(evaluation == AnimationEvaluation::Cpu ? "CPU evaluation" : "GPU evaluation");
        RendererOptions options = test::pixelTestOptions(kSize, kSize);
        options.animation = evaluation;
        const auto reference = renderAt(scene, StrategyKind::Materials, times);
        for (StrategyKind kind : {StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
            SCOPED_TRACE(std::string(strategyName(kind)));
            auto renderer = Renderer::create(*context, options);
            ASSERT_TRUE(renderer.ok());
            ASSERT_TRUE(renderer->prepare(scene, kind).ok());
            std::uint64_t recorded = 0;
            for (std::size_t i = 0; i < times.size(); ++i) {
                SCOPED_TRACE("t = " + std::to_string(times[i]));
                ASSERT_TRUE(renderer->setAnimationTime(times[i]).ok());
                renderer->renderFrame(frontCamera());
                auto image = renderer->readImage();
                ASSERT_TRUE(image.ok()) << image.error().message;
                EXPECT_EQ(test::differingPixels(*image, reference[i], 0), 0u);
                const GpuCuller& culler = *internals(*renderer).strategy()->report().culler;
                const auto counts = test::culledInstanceCounts(*context, culler);
                std::vector<std::uint32_t> visibleOfMesh(3, 0);
                for (std::size_t draw = 0; draw < counts.size(); ++draw) {
                    const auto first = culler.draws()[draw].instances.first;
                    const auto instance = static_cast<std::size_t>(
                        std::find(slots.begin(), slots.end(), first) - slots.begin());
                    visibleOfMesh[scene.instances[instance].mesh.index()] += counts[draw];
                }
                EXPECT_EQ(visibleOfMesh, expected[i]);
                if (i == 0) {
                    recorded = internals(*renderer).strategy()->report().bundlesRecorded;
                }
            }
            EXPECT_EQ(internals(*renderer).strategy()->report().bundlesRecorded, recorded);
            EXPECT_TRUE(context->checkNoErrors("animated culling").ok());
        }
    }
}

// The visibility strategy tests items against the frustum by world spheres while transforms
// hold still: after a still frame (its spheres computed), the animation moving the quads across
// the frustum's edge, evaluated on the CPU or the GPU, draws each frame as `materials` does.
TEST(AnimationRenderTest, VisibilityFollowsAnimationAcrossTheFrustumEdge) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = crossingScene();
    const std::vector<double> times = {0.0, 0.25, 0.5, 0.75, 1.0};
    const auto reference = renderAt(scene, StrategyKind::Materials, times);
    for (AnimationEvaluation evaluation : {AnimationEvaluation::Cpu, AnimationEvaluation::Gpu}) {
        SCOPED_TRACE(evaluation == AnimationEvaluation::Cpu ? "CPU evaluation" : "GPU evaluation");
        RendererOptions options = test::pixelTestOptions(kSize, kSize);
        options.animation = evaluation;
        auto renderer = Renderer::create(*context, options);
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Visibility).ok());
        for (std::size_t i = 0; i < times.size(); ++i) {
            ASSERT_TRUE(renderer->setAnimationTime(times[i]).ok());
            for (const char* frame : {"the animated frame", "a still frame after it"}) {
                SCOPED_TRACE("t = " + std::to_string(times[i]) + ", " + frame);
                renderer->renderFrame(frontCamera());
                auto image = renderer->readImage();
                ASSERT_TRUE(image.ok()) << image.error().message;
                const std::size_t pixels = std::size_t(image->width) * image->height;
                EXPECT_LE(double(test::differingPixels(*image, reference[i], 2)),
                          0.005 * double(pixels));
                EXPECT_EQ(
                    test::coveredFraction(*image, test::pixelAt(*image, 0, 0)) > 0.0,
                    test::coveredFraction(reference[i], test::pixelAt(reference[i], 0, 0)) > 0.0);
            }
        }
        EXPECT_TRUE(context->checkNoErrors("visibility animated across the frustum").ok());
    }
}

// 100 animated frames replay the bundles recorded once; every frame equals `materials`.
TEST(AnimationRenderTest, BundlesStayRecordedWhileAnimating) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = skinnedScene();
    const auto morph = morphedScene();
    for (const scene::SceneData* animated : {&scene, &morph}) {
        for (StrategyKind kind : {StrategyKind::Bundles, StrategyKind::GpuCullingBundles}) {
            SCOPED_TRACE(std::string(strategyName(kind)));
            auto bundled = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
            auto direct = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
            ASSERT_TRUE(bundled.ok() && direct.ok());
            ASSERT_TRUE(bundled->prepare(*animated, kind).ok());
            ASSERT_TRUE(direct->prepare(*animated, StrategyKind::Materials).ok());
            bundled->renderFrame(frontCamera());
            const std::uint64_t recorded = internals(*bundled).strategy()->report().bundlesRecorded;
            for (int frame = 0; frame < 100; ++frame) {
                const double t = frame / 99.0;
                ASSERT_TRUE(bundled->setAnimationTime(t).ok());
                bundled->renderFrame(frontCamera());
                if (frame % 33 == 0) {
                    ASSERT_TRUE(direct->setAnimationTime(t).ok());
                    direct->renderFrame(frontCamera());
                    auto a = bundled->readImage();
                    auto b = direct->readImage();
                    ASSERT_TRUE(a.ok() && b.ok());
                    EXPECT_EQ(test::differingPixels(*a, *b, 0), 0u) << "frame " << frame;
                }
            }
            EXPECT_EQ(internals(*bundled).strategy()->report().bundlesRecorded, recorded);
            auto errors = context->checkNoErrors("animating bundles");
            EXPECT_TRUE(errors.ok()) << errors.error().message;
        }
    }
}

TEST(AnimationRenderTest, SelectsOneAnimationByName) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = morphedScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    EXPECT_TRUE(renderer->selectAnimation("0").ok());
    EXPECT_FALSE(renderer->selectAnimation("no such animation").ok());
    ASSERT_TRUE(renderer->setAnimationTime(1.0).ok());
    EXPECT_EQ(renderer->animationStats().player.channelsEvaluated, 1u);
    EXPECT_GT(renderer->animationStats().upload.weightsWritten, 0u);
    EXPECT_GT(renderer->animationStats().bytesWritten, 0u);
}

// The Khronos sample models: different images at two times, equal across strategies.
class AnimatedModelTest : public ::testing::TestWithParam<const char*> {};

// The model's .glb among the shared models; nothing when they or it are absent.
std::optional<std::filesystem::path> sharedModel(const std::string& name) {
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        return std::nullopt;
    }
    auto path = *dir / name / "glTF-Binary" / (name + ".glb");
    if (!std::filesystem::exists(path)) {
        return std::nullopt;
    }
    return path;
}

TEST_P(AnimatedModelTest, ChangesOverTimeAndAgreesAcrossStrategies) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto path = sharedModel(GetParam());
    if (!path) {
        GTEST_SKIP() << GetParam() << " is absent from the shared models.";
    }
    auto scene = scene::loadScene(*path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_FALSE(scene->animations.empty());
    // Only the first animation: Fox's later ones drive the same joints, and a clamped loop ends
    // where it started.
    const double later = std::max(0.2, 0.37 * scene->animations[0].end);
    const Camera camera = Camera::framing(scene->bounds, 1.0f, 0.5f);
    std::vector<image::ImageRgba8> unlit, materials;
    for (StrategyKind kind : allStrategies()) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        const auto images = renderAt(*scene, kind, {0.0, later}, camera, "0");
        ASSERT_EQ(images.size(), 2u);
        EXPECT_GT(test::coveredFraction(images[0], test::pixelAt(images[0], 0, 0)), 0.02)
            << "the model is not in the picture";
        // CesiumMilkTruck only turns its wheels, which the vertex-colour strategies barely show.
        EXPECT_GT(test::differingPixels(images[0], images[1], 2), 0u)
            << "the animation changes nothing";
        auto& reference = hasMaterials(kind) ? materials : unlit;
        if (reference.empty()) {
            reference = images;
            continue;
        }
        for (std::size_t i = 0; i < 2; ++i) {
            if (kind == StrategyKind::Visibility) {
                // Shaded in compute with explicit texture gradients: close, not identical
                // (docs/visibility.md; VisibilityStrategyTest holds the same bound).
                const std::size_t pixels = std::size_t(images[i].width) * images[i].height;
                EXPECT_LE(double(test::differingPixels(images[i], reference[i], 2)),
                          0.015 * double(pixels))
                    << "frame " << i;
                continue;
            }
            EXPECT_EQ(test::differingPixels(images[i], reference[i], 0), 0u) << "frame " << i;
        }
    }
}

// Every animation of the file plays, chosen by name (or index when unnamed), through bundles
// recorded once: each moves the model, and two animations at the same time differ (Fox's
// Survey, Walk and Run drive the same joints differently).
TEST_P(AnimatedModelTest, EveryAnimationPlaysThroughBundles) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto path = sharedModel(GetParam());
    if (!path) {
        GTEST_SKIP() << GetParam() << " is absent from the shared models.";
    }
    auto scene = scene::loadScene(*path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Camera camera = Camera::framing(scene->bounds, 1.0f, 0.5f);
    std::vector<image::ImageRgba8> middles;
    for (std::size_t index = 0; index < scene->animations.size(); ++index) {
        const scene::Animation& animation = scene->animations[index];
        const std::string selector =
            animation.name.empty() ? std::to_string(index) : animation.name;
        SCOPED_TRACE("animation " + selector);
        const double start = animation.start;
        const double length = std::max(animation.end - start, 0.2);
        const auto images =
            renderAt(*scene, StrategyKind::Bundles, {start + 0.25 * length, start + 0.6 * length},
                     camera, selector);
        ASSERT_EQ(images.size(), 2u);
        EXPECT_GT(test::differingPixels(images[0], images[1], 2), 0u)
            << "the animation changes nothing";
        for (std::size_t other = 0; other < middles.size(); ++other) {
            EXPECT_GT(test::differingPixels(images[1], middles[other], 2), 0u)
                << "animation " << index << " looks like animation " << other;
        }
        middles.push_back(images[1]);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Models,
    AnimatedModelTest,
    ::testing::Values("Fox", "BrainStem", "CesiumMilkTruck", "AnimatedMorphCube"));

}  // namespace
}  // namespace encore::render
