// GPU-evaluated animation (render::GpuAnimation): the local, world, joint and instance matrices
// and the morph weights it computes, read back and compared with scene::AnimationPlayer's, for a
// generated scene covering STEP, LINEAR and CUBICSPLINE, a deep hierarchy, eight joints per
// vertex and morph weights, and for every animated shared model; frames rendered with it equal
// the CPU path's in every strategy, and bundles stay recorded while it plays.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "render/renderer/RendererCore.h"
#include "scene/CrowdGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
// Matrices and weights agree within 1e-4, relative to the CPU value where it exceeds 1.
constexpr float kTolerance = 1e-4f;

using test::frontCamera;

scene::SceneData load(const test::GltfBuilder& builder, const std::string& name) {
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, name);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

nlohmann::json sampler(test::GltfBuilder& builder,
                       const std::vector<float>& times,
                       const std::vector<float>& values,
                       const std::string& type,
                       const std::string& interpolation) {
    const auto input = builder.addAccessor<float>(times, "SCALAR", {.minMax = true});
    const auto output = builder.addAccessor<float>(values, type);
    return {{"input", input}, {"output", output}, {"interpolation", interpolation}};
}

glm::quat aboutZ(float angle) {
    return glm::angleAxis(angle, glm::vec3(0, 0, 1));
}

// LINEAR rotation keys about +Z, as glTF x, y, z, w.
std::vector<float> rotationKeys(const std::vector<float>& angles) {
    std::vector<float> values;
    for (float angle : angles) {
        const glm::quat q = aboutZ(angle);
        values.insert(values.end(), {q.x, q.y, q.z, q.w});
    }
    return values;
}

// A scene that exercises every part of the GPU path without the shared models:
//  - a root given by a matrix (not animated) above a chain of 8 joints, 9 levels deep, each
//    joint turning (LINEAR, slerp), joint 2 translated (STEP), joint 4 scaled (CUBICSPLINE);
//  - a quad skinned to all 8 joints with 8 weights per vertex (JOINTS_0/1, WEIGHTS_0/1);
//  - a quad with two morph targets whose weights follow a CUBICSPLINE sampler;
//  - a rigid quad on a node below joint 3 (instance transforms), translated (LINEAR);
//  - a second animation ("override") that also turns joint 1: with both selected it wins.
scene::SceneData generatedScene() {
    test::GltfBuilder builder;
    const auto material = builder.addMaterial({.baseColor = {1, 0, 0, 1}, .doubleSided = true});
    auto quad = [&](glm::vec3 center, float h) {
        test::GltfBuilder::PrimitiveDesc primitive;
        primitive.attributes["POSITION"] =
            builder.addPositions({center + glm::vec3(-h, -h, 0), center + glm::vec3(h, -h, 0),
                                  center + glm::vec3(h, h, 0), center + glm::vec3(-h, h, 0)});
        primitive.attributes["NORMAL"] =
            builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
        primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        primitive.material = material;
        return primitive;
    };

    // The joint chain: joint k at (0, 0.15) from its parent.
    std::vector<std::uint32_t> joints(8);
    for (int k = 7; k >= 0; --k) {
        test::GltfBuilder::NodeDesc node{.translation = glm::vec3(0, 0.15f, 0),
                                         .name = "joint" + std::to_string(k)};
        if (k < 7) {
            node.children = {joints[k + 1]};
        }
        joints[k] = builder.addNode(node);
    }
    // The rigid quad hangs below joint 3.
    auto rigid = quad({0, 0, 0}, 0.2f);
    const auto rigidMesh = builder.addMesh(rigid);
    const auto rigidNode =
        builder.addNode({.mesh = rigidMesh, .translation = glm::vec3(0.5f, 0, 0), .name = "rigid"});
    builder.json()["nodes"][joints[3]]["children"].push_back(rigidNode);
    const glm::mat4 rootMatrix = glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, -0.6f, 0.0f)) *
                                 glm::mat4_cast(aboutZ(0.1f));
    const auto root =
        builder.addNode({.children = {joints[0]}, .matrix = rootMatrix, .name = "root"});

    // Skinned quad: vertex v weighs all 8 joints, differently per vertex.
    auto skinned = quad({0, 0.6f, 0}, 0.3f);
    std::vector<std::uint8_t> joints0, joints1;
    std::vector<float> weights0, weights1;
    for (int v = 0; v < 4; ++v) {
        float w[8];
        float sum = 0;
        for (int j = 0; j < 8; ++j) {
            w[j] = 1.0f + float((v + j) % 4);
            sum += w[j];
        }
        for (int j = 0; j < 4; ++j) {
            joints0.push_back(std::uint8_t(j));
            joints1.push_back(std::uint8_t(j + 4));
            weights0.push_back(w[j] / sum);
            weights1.push_back(w[j + 4] / sum);
        }
    }
    skinned.attributes["JOINTS_0"] = builder.addAccessor<std::uint8_t>(joints0, "VEC4");
    skinned.attributes["JOINTS_1"] = builder.addAccessor<std::uint8_t>(joints1, "VEC4");
    skinned.attributes["WEIGHTS_0"] = builder.addAccessor<float>(weights0, "VEC4");
    skinned.attributes["WEIGHTS_1"] = builder.addAccessor<float>(weights1, "VEC4");
    const auto skinnedMesh = builder.addMesh(skinned);
    const auto skinnedNode = builder.addNode({.mesh = skinnedMesh, .name = "skinned"});
    builder.json()["nodes"][skinnedNode]["skin"] = 0;
    // Inverse bind matrices: the inverse of each joint's rest world matrix.
    std::vector<float> inverseBinds;
    glm::mat4 world = rootMatrix;
    for (int k = 0; k < 8; ++k) {
        world = world * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.15f, 0));
        const glm::mat4 inverse = glm::inverse(world);
        inverseBinds.insert(inverseBinds.end(), &inverse[0][0], &inverse[0][0] + 16);
    }
    const auto inverseBindAccessor = builder.addAccessor<float>(inverseBinds, "MAT4");
    nlohmann::json jointList = nlohmann::json::array();
    for (auto j : joints) {
        jointList.push_back(j);
    }
    builder.json()["skins"] = {
        {{"joints", jointList}, {"inverseBindMatrices", inverseBindAccessor}}};

    // Morphed quad with two targets.
    auto morphed = quad({1.2f, -0.8f, 0}, 0.25f);
    const auto morphedMesh = builder.addMesh(morphed);
    builder.json()["meshes"][morphedMesh]["primitives"][0]["targets"] = {
        {{"POSITION",
          builder.addPositions({{0.3f, 0, 0}, {0.3f, 0, 0}, {0.3f, 0, 0}, {0.3f, 0, 0}})}},
        {{"POSITION",
          builder.addPositions({{0, 0.4f, 0}, {0, 0.4f, 0}, {0, 0.4f, 0}, {0, 0.4f, 0}})}}};
    builder.json()["meshes"][morphedMesh]["weights"] = {0.25, 0.0};
    const auto morphedNode = builder.addNode({.mesh = morphedMesh, .name = "morphed"});

    nlohmann::json samplers = nlohmann::json::array();
    nlohmann::json channels = nlohmann::json::array();
    auto channel = [&](nlohmann::json sampler, std::uint32_t node, const char* path) {
        channels.push_back(
            {{"sampler", samplers.size()}, {"target", {{"node", node}, {"path", path}}}});
        samplers.push_back(std::move(sampler));
    };
    for (int k = 0; k < 8; ++k) {
        const float a = 0.15f * float(k + 1);
        channel(sampler(builder, {0.0f, 0.5f, 1.0f}, rotationKeys({0.0f, a, -2.0f * a}), "VEC4",
                        "LINEAR"),
                joints[k], "rotation");
    }
    channel(sampler(builder, {0.2f, 0.5f, 0.9f}, {0, 0.15f, 0, 0.1f, 0.2f, 0, -0.1f, 0.3f, 0},
                    "VEC3", "STEP"),
            joints[2], "translation");
    // CUBICSPLINE: per key in-tangent, value, out-tangent.
    channel(sampler(builder, {0.0f, 0.4f, 1.0f}, {0,    0,    0, 1,    1,    1, 2, 0.5f, 0,  //
                                                  -1,   1,    0, 1.3f, 0.8f, 1, 0, -2,   0,  //
                                                  0.5f, 0.5f, 0, 0.7f, 1.2f, 1, 0, 0,    0},
                    "VEC3", "CUBICSPLINE"),
            joints[4], "scale");
    channel(sampler(builder, {0.0f, 1.0f}, {0, 0, 0, 0.3f, -0.5f, 0}, "VEC3", "LINEAR"), rigidNode,
            "translation");
    channel(sampler(builder, {0.0f, 0.3f, 1.0f},
                    {0, 0, 0.25f, 0, 1, 2,  //
                     3, -1, 1, 0.5f, 0, 0,  //
                     -1, 0, 0, 1, 0, 0},
                    "SCALAR", "CUBICSPLINE"),
            morphedNode, "weights");
    builder.json()["animations"].push_back(
        {{"name", "main"}, {"samplers", samplers}, {"channels", channels}});
    builder.json()["animations"].push_back(
        {{"name", "override"},
         {"samplers",
          {sampler(builder, {0.0f, 0.75f}, rotationKeys({0.5f, -0.5f}), "VEC4", "LINEAR")}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", joints[1]}, {"path", "rotation"}}}}}}});
    builder.addScene({root, skinnedNode, morphedNode});
    return load(builder, "gpu-animation.glb");
}

template <typename T>
std::vector<T> readAll(gpu::Context& context, const wgpu::Buffer& buffer, std::size_t count) {
    auto bytes = gpu::readBuffer(context, buffer, 0, count * sizeof(T));
    EXPECT_TRUE(bytes.ok()) << bytes.error().message;
    std::vector<T> values(count);
    if (bytes.ok()) {
        std::memcpy(values.data(), bytes->data(), count * sizeof(T));
    }
    return values;
}

bool close(float gpu, float cpu) {
    return std::abs(gpu - cpu) <= kTolerance * std::max(1.0f, std::abs(cpu));
}

// Counts entries that differ, reporting the first few.
int expectMatrices(std::span<const glm::mat4> gpu,
                   std::span<const glm::mat4> cpu,
                   const std::string& what) {
    int bad = 0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                if (!close(gpu[i][c][r], cpu[i][c][r])) {
                    if (++bad <= 3) {
                        ADD_FAILURE() << what << " " << i << " [" << c << "][" << r << "]: GPU "
                                      << gpu[i][c][r] << ", CPU " << cpu[i][c][r];
                    }
                }
            }
        }
    }
    return bad;
}

struct Transform {
    glm::mat4 world;
    glm::mat4 normal;
};

// Renders one frame with GPU evaluation at each time and compares everything it wrote with a
// CPU player's evaluation at the same time.
void expectGpuMatchesCpu(gpu::Context& context,
                         const scene::SceneData& scene,
                         const std::vector<double>& times,
                         const std::string& animation = {},
                         scene::PlaybackMode mode = scene::PlaybackMode::Clamp) {
    auto options = test::pixelTestOptions(kSize, kSize);
    options.animation = AnimationEvaluation::Gpu;
    auto renderer = Renderer::create(context, options);
    ASSERT_TRUE(renderer.ok());
    renderer->setPlaybackMode(mode);
    auto prepared = renderer->prepare(scene, StrategyKind::Instancing);
    ASSERT_TRUE(prepared.ok()) << prepared.error().message;
    ASSERT_TRUE(renderer->selectAnimation(animation).ok());
    const GpuAnimation* gpu = internals(*renderer).gpuAnimation();
    ASSERT_NE(gpu, nullptr);
    const AnimationBuffers* buffers = internals(*renderer).animationBuffers();
    const InstanceTransformTargets targets =
        internals(*renderer).strategy()->instanceTransformTargets();

    scene::AnimationPlayer player(scene);
    player.setMode(mode);
    if (!animation.empty()) {
        ASSERT_TRUE(player.select(animation).ok());
    }
    for (double t : times) {
        SCOPED_TRACE("t = " + std::to_string(t));
        ASSERT_TRUE(renderer->setAnimationTime(t).ok());
        renderer->renderFrame(frontCamera());
        player.evaluate(t);
        const std::size_t nodes = scene.nodes.size();
        expectMatrices(readAll<glm::mat4>(context, gpu->locals(), nodes), player.nodeLocals(),
                       "local matrix of node");
        expectMatrices(readAll<glm::mat4>(context, gpu->worlds(), nodes), player.nodeWorlds(),
                       "world matrix of node");
        const auto joints = player.jointMatrices();
        if (buffers && !joints.empty()) {
            const auto transforms =
                readAll<Transform>(context, buffers->jointBuffer(), joints.size());
            std::vector<glm::mat4> worlds, normals;
            for (const Transform& transform : transforms) {
                worlds.push_back(transform.world);
                normals.push_back(transform.normal);
            }
            expectMatrices(worlds, joints, "joint matrix");
            expectMatrices(normals, player.jointNormalMatrices(), "joint normal matrix");
        }
        const auto weights = player.morphWeights();
        if (buffers && !weights.empty()) {
            const auto read = readAll<float>(context, buffers->weightBuffer(), weights.size());
            for (std::size_t w = 0; w < weights.size(); ++w) {
                EXPECT_TRUE(close(read[w], weights[w]))
                    << "morph weight " << w << ": GPU " << read[w] << ", CPU " << weights[w];
            }
        }
        const auto all = readAll<Transform>(context, targets.storage, scene.instances.size());
        std::vector<glm::mat4> worlds, normals;
        for (std::size_t i = 0; i < scene.instances.size(); ++i) {
            worlds.push_back(all[targets.slots[i]].world);
            glm::mat4 normal = all[targets.slots[i]].normal;
            // The fourth column carries the segmentation ids (1 + node, 1 + mesh), kept by the
            // animation pass; the normal matrix is the rest.
            EXPECT_EQ(normal[3].x, float(scene.instances[i].node.index() + 1)) << "instance " << i;
            EXPECT_EQ(normal[3].y, float(scene.instances[i].mesh.index() + 1)) << "instance " << i;
            normal[3].x = normal[3].y = 0.0f;
            normals.push_back(normal);
        }
        expectMatrices(worlds, player.instanceWorlds(), "instance world matrix");
        expectMatrices(normals, player.instanceNormalMatrices(), "instance normal matrix");
    }
    auto errors = context.checkNoErrors("GPU animation");
    EXPECT_TRUE(errors.ok()) << errors.error().message;
}

TEST(GpuAnimationTest, GeneratedSceneMatchesTheCpuPlayer) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generatedScene();
    ASSERT_EQ(scene.animations.size(), 2u);
    ASSERT_EQ(scene.skins.size(), 1u);
    // Before the first key, on keys (0.5, 0.4, 0.2, 1.0), between keys, after the last.
    const std::vector<double> times = {-0.5, 0.0, 0.1, 0.2, 0.4, 0.5, 0.63, 0.75, 0.9, 1.0, 1.7};
    expectGpuMatchesCpu(*context, scene, times);
    expectGpuMatchesCpu(*context, scene, times, "main");
    expectGpuMatchesCpu(*context, scene, times, "override");
}

TEST(GpuAnimationTest, ReportsItsSize) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generatedScene();
    auto options = test::pixelTestOptions(kSize, kSize);
    auto renderer = Renderer::create(*context, options);
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    EXPECT_EQ(internals(*renderer).gpuAnimation(), nullptr);
    ASSERT_TRUE(renderer->setAnimationEvaluation(AnimationEvaluation::Gpu).ok());
    ASSERT_NE(internals(*renderer).gpuAnimation(), nullptr);
    const GpuAnimationStats& stats = internals(*renderer).gpuAnimation()->stats();
    EXPECT_EQ(stats.animatedNodes, 10u);  // 8 joints, the rigid node, the morphed node.
    EXPECT_EQ(stats.levels, 9u);          // joint0 (depth 1) .. joint7, the rigid node at 5.
    EXPECT_EQ(stats.joints, 8u);
    // The rigid quad and the morphed one (its node has a weights channel); the skinned quad's
    // node does not move.
    EXPECT_EQ(stats.instances, 2u);
    EXPECT_EQ(stats.dispatches, 1u + 9u + 2u);
    ASSERT_TRUE(renderer->setAnimationTime(0.3).ok());
    EXPECT_EQ(renderer->animationStats().evaluation, AnimationEvaluation::Gpu);
    EXPECT_EQ(renderer->animationStats().bytesWritten, 2u * sizeof(float));
    EXPECT_EQ(renderer->animationStats().player.channelsEvaluated, 0u);
}

// Every strategy draws the same frame with either evaluation.
void expectSameFrames(gpu::Context& context,
                      const scene::SceneData& scene,
                      const std::vector<double>& times,
                      const Camera& camera,
                      const std::string& animation = {}) {
    for (StrategyKind kind : allStrategies()) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        auto cpu = Renderer::create(context, test::pixelTestOptions(kSize, kSize));
        auto options = test::pixelTestOptions(kSize, kSize);
        options.animation = AnimationEvaluation::Gpu;
        auto gpu = Renderer::create(context, options);
        ASSERT_TRUE(cpu.ok() && gpu.ok());
        ASSERT_TRUE(cpu->prepare(scene, kind).ok());
        auto prepared = gpu->prepare(scene, kind);
        ASSERT_TRUE(prepared.ok()) << prepared.error().message;
        ASSERT_TRUE(cpu->selectAnimation(animation).ok());
        ASSERT_TRUE(gpu->selectAnimation(animation).ok());
        gpu->renderFrame(camera);
        auto rest = gpu->readImage();
        ASSERT_TRUE(rest.ok());
        std::size_t moved = 0;  // Frames that differ from the rest pose: the test sees motion.
        for (double t : times) {
            ASSERT_TRUE(cpu->setAnimationTime(t).ok());
            ASSERT_TRUE(gpu->setAnimationTime(t).ok());
            cpu->renderFrame(camera);
            gpu->renderFrame(camera);
            auto a = cpu->readImage();
            auto b = gpu->readImage();
            ASSERT_TRUE(a.ok() && b.ok());
            EXPECT_EQ(test::differingPixels(*a, *b, 0), 0u) << "t = " << t;
            moved += test::differingPixels(*b, *rest, 2) > 0 ? 1 : 0;
        }
        EXPECT_GT(moved, 0u) << "no frame differs from the rest pose";
        auto errors = context.checkNoErrors("GPU animation frames");
        EXPECT_TRUE(errors.ok()) << errors.error().message;
    }
}

TEST(GpuAnimationTest, FramesEqualTheCpuPathInEveryStrategy) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generatedScene();
    expectSameFrames(*context, scene, {0.0, 0.3, 0.5, 0.8, 1.5}, frontCamera());
}

TEST(GpuAnimationTest, BundlesStayRecordedOverManyGpuFrames) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generatedScene();
    for (StrategyKind kind : {StrategyKind::Bundles, StrategyKind::GpuCullingBundles}) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        auto options = test::pixelTestOptions(kSize, kSize);
        options.animation = AnimationEvaluation::Gpu;
        auto gpu = Renderer::create(*context, options);
        auto cpu = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
        ASSERT_TRUE(gpu.ok() && cpu.ok());
        ASSERT_TRUE(gpu->prepare(scene, kind).ok());
        ASSERT_TRUE(cpu->prepare(scene, kind).ok());
        gpu->renderFrame(frontCamera());
        const std::uint64_t recorded = internals(*gpu).strategy()->report().bundlesRecorded;
        for (int frame = 0; frame < 120; ++frame) {
            const double t = frame / 100.0;
            ASSERT_TRUE(gpu->setAnimationTime(t).ok());
            gpu->renderFrame(frontCamera());
            if (frame % 40 == 7) {
                ASSERT_TRUE(cpu->setAnimationTime(t).ok());
                cpu->renderFrame(frontCamera());
                auto a = gpu->readImage();
                auto b = cpu->readImage();
                ASSERT_TRUE(a.ok() && b.ok());
                EXPECT_EQ(test::differingPixels(*a, *b, 0), 0u) << "frame " << frame;
            }
        }
        EXPECT_EQ(internals(*gpu).strategy()->report().bundlesRecorded, recorded);
        auto errors = context->checkNoErrors("GPU animation with bundles");
        EXPECT_TRUE(errors.ok()) << errors.error().message;
    }
}

// Switching back to the CPU rewrites everything the GPU wrote.
TEST(GpuAnimationTest, SwitchingEvaluationKeepsTheFrame) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto scene = generatedScene();
    auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    auto reference = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
    ASSERT_TRUE(renderer.ok() && reference.ok());
    ASSERT_TRUE(renderer->prepare(scene, StrategyKind::Materials).ok());
    ASSERT_TRUE(reference->prepare(scene, StrategyKind::Materials).ok());
    ASSERT_TRUE(renderer->setAnimationEvaluation(AnimationEvaluation::Gpu).ok());
    ASSERT_TRUE(renderer->setAnimationTime(0.7).ok());
    renderer->renderFrame(frontCamera());
    ASSERT_TRUE(renderer->setAnimationEvaluation(AnimationEvaluation::Cpu).ok());
    ASSERT_TRUE(renderer->setAnimationTime(0.2).ok());
    renderer->renderFrame(frontCamera());
    ASSERT_TRUE(reference->setAnimationTime(0.2).ok());
    reference->renderFrame(frontCamera());
    auto a = renderer->readImage();
    auto b = reference->readImage();
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(test::differingPixels(*a, *b, 0), 0u);
}

// The generated crowd (encore gen --crowd): its characters play with different time offsets,
// and the GPU evaluates it as the CPU does.
TEST(GpuAnimationTest, CrowdMatchesTheCpuPlayer) {
    ENCORE_REQUIRE_VULKAN(context);
    auto glb = scene::generateCrowdGlb({5});
    ASSERT_TRUE(glb.ok()) << glb.error().message;
    auto crowd = scene::loadSceneFromMemory(*glb, {}, "crowd.glb");
    ASSERT_TRUE(crowd.ok()) << crowd.error().message;
    EXPECT_EQ(crowd->instances.size(), 5u);
    EXPECT_EQ(crowd->skins.size(), 5u);
    EXPECT_EQ(crowd->nodes.size(), 5u * scene::kCrowdNodesPerCharacter);
    // One animation per character, same keys, each with its own time offset.
    ASSERT_EQ(crowd->animations.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) {
        EXPECT_EQ(crowd->animations[k].channels.size(), scene::kCrowdJointsPerCharacter);
        EXPECT_EQ(crowd->animations[k].end, 1.0f);
        EXPECT_NEAR(crowd->animations[k].timeOffset, std::fmod(0.37 * double(k), 1.0), 1e-6);
        EXPECT_EQ(crowd->animations[k].samplers[2].times, crowd->animations[0].samplers[2].times);
        EXPECT_EQ(crowd->animations[k].samplers[2].values, crowd->animations[0].samplers[2].values);
    }
    // Different offsets: at t = 0.3 the first two characters are in different poses.
    scene::AnimationPlayer player(*crowd);
    player.evaluate(0.3);
    const auto joints = player.jointMatrices();
    const auto offsets = player.skinJointOffsets();
    EXPECT_NE(joints[offsets[0] + 3][0], joints[offsets[1] + 3][0]);
    const std::vector<double> times = {-1.0, 0.0, 0.3, 0.74, 1.0, 1.5, 3.0, 7.81};
    expectGpuMatchesCpu(*context, *crowd, times);
    expectGpuMatchesCpu(*context, *crowd, times, {}, scene::PlaybackMode::Loop);
    expectGpuMatchesCpu(*context, *crowd, times, "sway 3", scene::PlaybackMode::Loop);
    expectSameFrames(*context, *crowd, {0.5, 1.2}, Camera::framing(crowd->bounds, 1.0f, 0.5f));
    auto refused = scene::generateCrowdGlb({0});
    EXPECT_FALSE(refused.ok());
}

// The GPU stores a crowd's keyframes once and gives its characters one clock: what it keeps and
// what the CPU writes per frame do not grow with the characters.
TEST(GpuAnimationTest, ACrowdSharesItsKeyframesAndOneClock) {
    ENCORE_REQUIRE_VULKAN(context);
    std::vector<GpuAnimationStats> sizes;
    for (std::uint32_t characters : {4u, 64u}) {
        auto glb = scene::generateCrowdGlb({characters});
        ASSERT_TRUE(glb.ok()) << glb.error().message;
        auto crowd = scene::loadSceneFromMemory(*glb, {}, "crowd.glb");
        ASSERT_TRUE(crowd.ok()) << crowd.error().message;
        auto options = test::pixelTestOptions(kSize, kSize);
        options.animation = AnimationEvaluation::Gpu;
        auto renderer = Renderer::create(*context, options);
        ASSERT_TRUE(renderer.ok());
        renderer->setPlaybackMode(scene::PlaybackMode::Loop);
        ASSERT_TRUE(renderer->prepare(*crowd, StrategyKind::GpuCullingBundles).ok());
        ASSERT_NE(internals(*renderer).gpuAnimation(), nullptr);
        sizes.push_back(internals(*renderer).gpuAnimation()->stats());
        ASSERT_TRUE(renderer->setAnimationTime(0.5).ok());
        ASSERT_TRUE(renderer->setAnimationTime(12.25).ok());
        EXPECT_EQ(renderer->animationStats().bytesWritten, sizeof(float)) << characters;
        EXPECT_EQ(sizes.back().joints, characters * scene::kCrowdJointsPerCharacter);
    }
    EXPECT_EQ(sizes[0].clocks, 1u);
    EXPECT_EQ(sizes[1].clocks, 1u);
    // 5 key times and 4 joints x 5 rotation keys, however many characters.
    EXPECT_EQ(sizes[0].keyframeBytes, (5u + 4u * 5u * 4u) * sizeof(float));
    EXPECT_EQ(sizes[1].keyframeBytes, sizes[0].keyframeBytes);
    EXPECT_EQ(sizes[1].bytesPerFrame, sizeof(float));
}

// Every animated model of ../shared/models (skipped without it).
std::vector<std::filesystem::path> animatedSharedModels() {
    std::vector<std::filesystem::path> found;
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        return found;
    }
    for (const auto& entry : std::filesystem::directory_iterator(*dir)) {
        if (!entry.is_directory()) {
            continue;
        }
        const std::string name = entry.path().filename().string();
        for (const auto& candidate : {entry.path() / "glTF-Binary" / (name + ".glb"),
                                      entry.path() / "glTF" / (name + ".gltf")}) {
            if (!std::filesystem::exists(candidate)) {
                continue;
            }
            auto scene = scene::loadScene(candidate, {.decodeImages = false});
            if (scene.ok() && !scene->animations.empty()) {
                found.push_back(candidate);
            }
            break;
        }
    }
    std::sort(found.begin(), found.end());
    return found;
}

// Times before the first key, exactly on keys, between keys and after the last key of the
// first animation's first sampler.
std::vector<double> interestingTimes(const scene::SceneData& scene) {
    std::vector<double> times = {-1.0};
    const scene::Animation& animation = scene.animations[0];
    const std::vector<float>& keys = animation.samplers[0].times;
    times.push_back(keys.front());
    if (keys.size() > 2) {
        const std::size_t k = keys.size() / 2;
        times.push_back(keys[k]);
        times.push_back(0.5 * (double(keys[k]) + double(keys[k + 1])));
        times.push_back(keys[k] + 0.3 * (double(keys[k + 1]) - keys[k]));
    }
    times.push_back(0.37 * animation.end);
    times.push_back(keys.back());
    times.push_back(animation.end + 1.0);
    return times;
}

TEST(GpuAnimationTest, SharedModelsMatchTheCpuPlayer) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto models = animatedSharedModels();
    if (models.empty()) {
        GTEST_SKIP() << "No animated model in the shared models directory (absent?).";
    }
    std::printf("animated shared models: %zu\n", models.size());
    for (const auto& path : models) {
        SCOPED_TRACE(path.filename().string());
        std::printf("  %s\n", path.filename().string().c_str());
        auto scene = scene::loadScene(path, {.decodeImages = false});
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        expectGpuMatchesCpu(*context, *scene, interestingTimes(*scene));
        expectGpuMatchesCpu(*context, *scene, interestingTimes(*scene), "0");
    }
}

TEST(GpuAnimationTest, SharedModelFramesEqualTheCpuPath) {
    ENCORE_REQUIRE_VULKAN(context);
    const auto models = animatedSharedModels();
    if (models.empty()) {
        GTEST_SKIP() << "No animated model in the shared models directory (absent?).";
    }
    for (const auto& path : models) {
        SCOPED_TRACE(path.filename().string());
        auto scene = scene::loadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        const Camera camera = Camera::framing(scene->bounds, 1.0f, 0.5f);
        expectSameFrames(*context, *scene, {0.37 * scene->animations[0].end}, camera, "0");
    }
}

}  // namespace
}  // namespace encore::render
