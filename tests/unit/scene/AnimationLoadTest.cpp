// Loading animations, skins and morph targets from in-code glTF: what SceneData holds, the
// errors for bad input (each naming the element), and the AnimationPlayer on small scenes.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "SceneTestUtils.h"
#include "encore/scene/AnimationPlayer.h"

namespace encore::scene {
namespace {

using testing::expectError;
using testing::loadGltf;
using json = nlohmann::json;

void expectMatrixNear(const glm::mat4& actual,
                      const glm::mat4& expected,
                      float tolerance,
                      const std::string& label = {}) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(actual[c][r], expected[c][r], tolerance)
                << label << " [" << c << "][" << r << "]";
        }
    }
}

// A scene whose root (node 0) carries the mesh child (node 1).
test::GltfBuilder hierarchy() {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto mesh = builder.addMesh({.attributes = {{"POSITION", positions}}});
    builder.json()["nodes"] = json::array();
    builder.json()["nodes"].push_back({{"name", "root"}, {"children", {1}}});
    builder.json()["nodes"].push_back(
        {{"name", "child"}, {"mesh", mesh}, {"translation", {0.0, 0.0, 1.0}}});
    builder.addScene({0});
    return builder;
}

void addAnimation(test::GltfBuilder& builder,
                  const std::string& name,
                  json samplers,
                  json channels) {
    builder.json()["animations"].push_back(
        {{"name", name}, {"samplers", std::move(samplers)}, {"channels", std::move(channels)}});
}

json channel(std::uint32_t sampler, std::uint32_t node, const std::string& path) {
    return {{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}};
}

json sampler(std::uint32_t input, std::uint32_t output, const std::string& mode = "LINEAR") {
    return {{"input", input}, {"output", output}, {"interpolation", mode}};
}

// An animation that slides the root from (0, 0, 0) through (2, 0, 0) to (2, 4, 0) in 2 s.
void addSlide(test::GltfBuilder& builder, const std::string& name) {
    const auto times = builder.addAccessor(std::vector<float>{0, 1, 2}, "SCALAR", {.minMax = true});
    const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 2, 0, 0, 2, 4, 0}, "VEC3");
    addAnimation(builder, name, {sampler(times, values)}, {channel(0, 0, "translation")});
}

TEST(AnimationLoadTest, TranslationChannelIsDecoded) {
    auto builder = hierarchy();
    addSlide(builder, "slide");
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->animations.size(), 1u);
    const Animation& animation = scene->animations[0];
    EXPECT_EQ(animation.name, "slide");
    EXPECT_EQ(animation.start, 0.0f);
    EXPECT_EQ(animation.end, 2.0f);
    ASSERT_EQ(animation.channels.size(), 1u);
    EXPECT_EQ(animation.channels[0].node, NodeId(0u));
    EXPECT_EQ(animation.channels[0].path, AnimationPath::Translation);
    EXPECT_EQ(animation.samplers[0].components, 3u);
    EXPECT_EQ(animation.samplers[0].values.size(), 9u);
    EXPECT_EQ(scene->nodes[1].translation, glm::vec3(0, 0, 1));
    EXPECT_FALSE(scene->nodes[1].hasMatrix);

    AnimationPlayer player(*scene);
    ASSERT_EQ(player.instanceWorlds().size(), 1u);
    expectMatrixNear(player.instanceWorlds()[0], scene->instances[0].world, 0.0f);
    player.evaluate(1.5);
    // Root at (2, 2, 0), child 1 further along z.
    expectMatrixNear(player.instanceWorlds()[0], glm::translate(glm::mat4(1.0f), {2, 2, 1}), 1e-6f);
    EXPECT_EQ(player.changedInstances().size(), 1u);
    EXPECT_EQ(player.stats().channelsEvaluated, 1u);
    // Clamped past the end: the pose stops, nothing changes twice.
    player.evaluate(5.0);
    expectMatrixNear(player.instanceWorlds()[0], glm::translate(glm::mat4(1.0f), {2, 4, 1}), 1e-6f);
    EXPECT_EQ(player.changedInstances().size(), 1u);
    player.evaluate(6.0);
    EXPECT_TRUE(player.changedInstances().empty());
    EXPECT_EQ(player.stats().worldsUpdated, 0u);
    // Looping: 5 s wraps to 1 s.
    player.setMode(PlaybackMode::Loop);
    player.evaluate(5.0);
    expectMatrixNear(player.instanceWorlds()[0], glm::translate(glm::mat4(1.0f), {2, 0, 1}), 1e-6f);
    // No animation selected: back to the loader's matrices, exactly.
    player.selectNone();
    player.evaluate(1.0);
    expectMatrixNear(player.instanceWorlds()[0], scene->instances[0].world, 0.0f);
    expectMatrixNear(player.instanceNormalMatrices()[0], scene->instances[0].normalMatrix, 0.0f);
    EXPECT_EQ(player.changedInstances().size(), 1u);
}

TEST(AnimationLoadTest, SelectionByNameOrIndex) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto short2 = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 0, 0}, "VEC3");
    const auto times4 = builder.addAccessor(std::vector<float>{0, 4}, "SCALAR");
    const auto scale = builder.addAccessor(std::vector<float>{1, 1, 1, 3, 3, 3}, "VEC3");
    addAnimation(builder, "move", {sampler(times, short2)}, {channel(0, 0, "translation")});
    addAnimation(builder, "grow", {sampler(times4, scale)}, {channel(0, 1, "scale")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(findAnimation(*scene, "grow"), AnimationId(1u));
    EXPECT_EQ(findAnimation(*scene, "0"), AnimationId(0u));
    EXPECT_FALSE(findAnimation(*scene, "2").has_value());
    EXPECT_FALSE(findAnimation(*scene, "run").has_value());

    AnimationPlayer player(*scene);
    EXPECT_EQ(player.selection().size(), 2u);
    EXPECT_EQ(player.duration(), 4.0f);
    ASSERT_TRUE(player.select("grow").ok());
    EXPECT_EQ(player.duration(), 4.0f);
    player.evaluate(2.0);
    EXPECT_EQ(player.translation(NodeId(0u)), glm::vec3(0.0f));
    EXPECT_EQ(player.scale(NodeId(1u)), glm::vec3(2.0f));
    ASSERT_TRUE(player.select("move").ok());
    EXPECT_EQ(player.duration(), 1.0f);
    player.evaluate(2.0);
    EXPECT_EQ(player.translation(NodeId(0u)), glm::vec3(1, 0, 0));
    EXPECT_EQ(player.scale(NodeId(1u)), glm::vec3(1.0f));  // Back to rest.
    const auto missing = player.select("run");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("'run'"), std::string::npos);
    EXPECT_FALSE(player.select(AnimationId(7u)).ok());
}

TEST(AnimationLoadTest, NormalisedIntegerRotationsAndStep) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    // Identity, then 90 degrees about z as normalised shorts: 23170 / 32767 = 0.70711.
    const auto rotations =
        builder.addAccessor(std::vector<std::int16_t>{0, 0, 0, 32767, 0, 0, 23170, 23170}, "VEC4",
                            {.normalized = true});
    addAnimation(builder, "turn", {sampler(times, rotations, "STEP")}, {channel(0, 1, "rotation")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const AnimationSampler& decoded = scene->animations[0].samplers[0];
    EXPECT_EQ(decoded.interpolation, Interpolation::Step);
    EXPECT_FLOAT_EQ(decoded.values[3], 1.0f);
    EXPECT_NEAR(decoded.values[6], 0.70711f, 1e-5f);
    AnimationPlayer player(*scene);
    player.evaluate(0.99);
    EXPECT_EQ(player.rotation(NodeId(1u)), glm::quat(1, 0, 0, 0));
    player.evaluate(1.0);
    const glm::vec4 x = player.nodeWorlds()[1] * glm::vec4(1, 0, 0, 0);
    EXPECT_NEAR(x.x, 0.0f, 1e-5f);
    EXPECT_NEAR(x.y, 1.0f, 1e-5f);
}

// A mesh with two morph targets on node 0; weights animated with the given output accessor.
test::GltfBuilder morphScene(std::optional<std::vector<float>> meshWeights = {},
                             std::optional<std::vector<float>> nodeWeights = {}) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto up = builder.addAccessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    // Quantised deltas: normalised bytes, 127 = 1.0.
    const auto right = builder.addAccessor(
        std::vector<std::int8_t>{127, 0, 0, 0, 127, 0, 0, 0, 127, 0}, "VEC3", {.normalized = true});
    builder.addMesh({.attributes = {{"POSITION", positions}}});
    builder.json()["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", up}},
                                                               {{"POSITION", right}}};
    if (meshWeights) {
        builder.json()["meshes"][0]["weights"] = *meshWeights;
    }
    builder.addScene({builder.addNode({.mesh = 0})});
    if (nodeWeights) {
        builder.json()["nodes"][0]["weights"] = *nodeWeights;
    }
    return builder;
}

TEST(AnimationLoadTest, MorphTargetsAndWeights) {
    auto builder = morphScene(std::vector<float>{0.25f, 0.5f});
    // Accessor indices: 0 positions, 1 up, 2 right (9 bytes of 10 values: count 3).
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = scene->meshes[0].primitives[0];
    ASSERT_EQ(primitive.targets.size(), 2u);
    ASSERT_TRUE(primitive.targets[1].position);
    EXPECT_FALSE(primitive.targets[1].normal);
    const Accessor& delta = scene->accessors[primitive.targets[1].position->index()];
    EXPECT_EQ(delta.componentType, ComponentType::Float32);
    EXPECT_EQ(delta.count, 3u);
    const auto values = scene->readFloats(*primitive.targets[1].position);
    EXPECT_EQ(values[0], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(values[1], glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(scene->meshes[0].weights, (std::vector<float>{0.25f, 0.5f}));
    EXPECT_EQ(scene->nodes[0].weights, (std::vector<float>{0.25f, 0.5f}));

    const auto overridden =
        loadGltf(morphScene(std::vector<float>{0.25f, 0.5f}, std::vector<float>{1.0f, 0.0f}));
    ASSERT_TRUE(overridden.ok()) << overridden.error().message;
    EXPECT_EQ(overridden->nodes[0].weights, (std::vector<float>{1.0f, 0.0f}));
    const auto zeros = loadGltf(morphScene());
    ASSERT_TRUE(zeros.ok()) << zeros.error().message;
    EXPECT_EQ(zeros->meshes[0].weights, (std::vector<float>{0.0f, 0.0f}));
}

TEST(AnimationLoadTest, NormalisedWeightsAnimation) {
    auto builder = morphScene();
    const auto times = builder.addAccessor(std::vector<float>{0, 2}, "SCALAR");
    // Two keys x two targets, normalised unsigned bytes.
    const auto weights = builder.addAccessor(std::vector<std::uint8_t>{0, 255, 255, 51}, "SCALAR",
                                             {.normalized = true});
    addAnimation(builder, "blend", {sampler(times, weights)}, {channel(0, 0, "weights")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->animations[0].samplers[0].components, 2u);
    AnimationPlayer player(*scene);
    ASSERT_EQ(player.instanceRanges().size(), 1u);
    EXPECT_EQ(player.instanceRanges()[0].weightOffset, 0u);
    EXPECT_EQ(player.instanceRanges()[0].weightCount, 2u);
    EXPECT_EQ(player.instanceRanges()[0].jointOffset, InstanceAnimationRange::kNone);
    player.evaluate(1.0);
    ASSERT_EQ(player.morphWeights().size(), 2u);
    EXPECT_FLOAT_EQ(player.morphWeights()[0], 0.5f);
    EXPECT_FLOAT_EQ(player.morphWeights()[1], 0.6f);  // (1 + 0.2) / 2.
    EXPECT_EQ(player.changedInstances().size(), 1u);
}

TEST(AnimationLoadTest, CubicSplineTranslation) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 2}, "SCALAR");
    // in, value, out per key (VEC3): x goes 0 -> 1 with out-tangent 3 and in-tangent -1.
    const auto values = builder.addAccessor(
        std::vector<float>{9, 0, 0, 0, 0, 0, 3, 0, 0, -1, 0, 0, 1, 0, 0, 9, 0, 0}, "VEC3");
    addAnimation(builder, "", {sampler(times, values, "CUBICSPLINE")},
                 {channel(0, 0, "translation")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    AnimationPlayer player(*scene);
    player.evaluate(1.0);
    EXPECT_FLOAT_EQ(player.translation(NodeId(0u)).x, 1.5f);  // See AnimationSamplerTest.
}

// A two-joint skin on node 0 (the mesh), joints 1 and 2 (2 is 1's child).
test::GltfBuilder skinScene(bool inverseBind, std::uint8_t largestJoint = 1) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto joints = builder.addAccessor(
        std::vector<std::uint8_t>{0, 1, 0, 0, 0, 1, 0, 0, largestJoint, 0, 0, 0}, "VEC4");
    const auto weights =
        builder.addAccessor(std::vector<float>{0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    builder.addMesh(
        {.attributes = {{"POSITION", positions}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}});
    builder.json()["nodes"] = json::array();
    builder.json()["nodes"].push_back({{"mesh", 0}, {"skin", 0}});
    builder.json()["nodes"].push_back({{"children", {2}}, {"translation", {0.0, 1.0, 0.0}}});
    builder.json()["nodes"].push_back({{"translation", {0.0, 1.0, 0.0}}});
    json skin = {{"joints", {1, 2}}, {"skeleton", 1}, {"name", "arm"}};
    if (inverseBind) {
        const glm::mat4 a = glm::translate(glm::mat4(1.0f), {0, -1, 0});
        const glm::mat4 b = glm::translate(glm::mat4(1.0f), {0, -2, 0});
        std::vector<float> matrices(32);
        std::memcpy(matrices.data(), &a[0][0], 64);
        std::memcpy(matrices.data() + 16, &b[0][0], 64);
        skin["inverseBindMatrices"] = builder.addAccessor(matrices, "MAT4");
    }
    builder.json()["skins"] = {skin};
    builder.addScene({0, 1});
    return builder;
}

TEST(AnimationLoadTest, SkinJointMatrices) {
    const auto scene = loadGltf(skinScene(true));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->skins.size(), 1u);
    const Skin& skin = scene->skins[0];
    EXPECT_EQ(skin.name, "arm");
    EXPECT_EQ(skin.joints, (std::vector<NodeId>{NodeId(1u), NodeId(2u)}));
    EXPECT_EQ(skin.skeleton, NodeId(1u));
    EXPECT_EQ(scene->nodes[0].skin, SkinId(0u));
    const Primitive& primitive = scene->meshes[0].primitives[0];
    EXPECT_TRUE(primitive.attribute(Semantic::Joints0));
    EXPECT_TRUE(primitive.attribute(Semantic::Weights0));

    AnimationPlayer player(*scene);
    // Bind pose: world(joint) * inverseBind is the identity.
    ASSERT_EQ(player.jointMatrices().size(), 2u);
    ASSERT_EQ(player.skinJointOffsets().size(), 1u);
    EXPECT_EQ(player.skinJointOffsets()[0], 0u);
    for (const glm::mat4& joint : player.jointMatrices()) {
        expectMatrixNear(joint, glm::mat4(1.0f), 1e-6f);
    }
    EXPECT_EQ(player.instanceRanges()[0].jointOffset, 0u);
    EXPECT_EQ(player.instanceRanges()[0].jointCount, 2u);

    // Without inverseBindMatrices: identity, so joint matrices are the joints' worlds.
    const auto identity = loadGltf(skinScene(false));
    ASSERT_TRUE(identity.ok()) << identity.error().message;
    EXPECT_EQ(identity->skins[0].inverseBindMatrices[1], glm::mat4(1.0f));
    AnimationPlayer bare(*identity);
    expectMatrixNear(bare.jointMatrices()[1], glm::translate(glm::mat4(1.0f), {0, 2, 0}), 0.0f);
}

TEST(AnimationLoadTest, AnimatedJointMovesItsChildAndTheSkin) {
    auto builder = skinScene(true);
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const float h = std::sqrt(0.5f);
    const auto rotations = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 0, 0, h, h}, "VEC4");
    addAnimation(builder, "bend", {sampler(times, rotations)}, {channel(0, 1, "rotation")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    AnimationPlayer player(*scene);
    player.evaluate(0.0);  // The first evaluation reports everything.
    EXPECT_EQ(player.changedInstances().size(), 1u);
    player.evaluate(1.0);
    ASSERT_EQ(player.changedSkins().size(), 1u);
    // Joint 1 turns 90 degrees about z at (0, 1, 0): joint 2's bind position (0, 2, 0) goes to
    // (-1, 1, 0); a vertex bound to joint 2 at (0, 2, 0) follows.
    const glm::vec4 moved = player.jointMatrices()[1] * glm::vec4(0, 2, 0, 1);
    EXPECT_NEAR(moved.x, -1.0f, 1e-6f);
    EXPECT_NEAR(moved.y, 1.0f, 1e-6f);
    const glm::mat4 expectedNormal = normalMatrixOf(player.jointMatrices()[1]);
    expectMatrixNear(player.jointNormalMatrices()[1], expectedNormal, 0.0f);
    // The mesh node is not under the joints: its instance does not move.
    EXPECT_TRUE(player.changedInstances().empty());
    player.evaluate(1.0);
    EXPECT_TRUE(player.changedSkins().empty());
}

// --- Errors ----------------------------------------------------------------------------------

TEST(AnimationLoadTest, ChannelTargetingAMissingNode) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
    addAnimation(builder, "", {sampler(times, values)},
                 {channel(0, 0, "scale"), channel(0, 17, "translation")});
    expectError(
        loadGltf(builder), ErrorCode::InvalidFormat,
        {"test.gltf: animation 0, channel 1 refers to node 17 (target)", "the asset has 2 nodes."});
}

TEST(AnimationLoadTest, ChannelSamplerOutOfRange) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
    addAnimation(builder, "", {sampler(times, values)}, {channel(3, 0, "scale")});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"animation 0, channel 0 refers to sampler 3", "the animation has 1 sampler."});
}

TEST(AnimationLoadTest, InputTimesMustBeIncreasingScalarFloats) {
    {
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<float>{0, 1, 1}, "SCALAR");
        const auto values =
            builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3");
        addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "scale")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0, sampler 0 has key times that are not strictly increasing",
                     "key 2 at 1 s follows 1 s"});
    }
    {
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<std::uint8_t>{0, 1}, "SCALAR");
        const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
        addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "scale")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0, sampler 0 has an input (accessor", "not a SCALAR of floats"});
    }
    {
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<float>{0, 1, 2, 3}, "VEC2");
        const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
        addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "scale")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"VEC2) that is not a SCALAR"});
    }
}

TEST(AnimationLoadTest, OutputCountMustMatchTheKeys) {
    {
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<float>{0, 1, 2}, "SCALAR");
        const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
        addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "scale")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0, sampler 0 has 2 output values", "for 3 key times"});
    }
    {
        // CUBICSPLINE needs 3 per key: 2 keys, 2 values is too few.
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
        const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
        addAnimation(builder, "", {sampler(times, values, "CUBICSPLINE")},
                     {channel(0, 0, "scale")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0, sampler 0 has 2 output values", "CUBICSPLINE needs 3"});
    }
    {
        // Twice as many values as keys: fine for weights of 2 targets, not for a translation.
        auto builder = hierarchy();
        const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
        const auto values =
            builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3}, "VEC3");
        addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "translation")});
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0, channel 0 animates translation",
                     "has 4 elements for 2 key "
                     "times (needs 2)"});
    }
}

TEST(AnimationLoadTest, OutputTypeMustFitThePath) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<std::int16_t>{0, 0, 0, 1, 1, 1}, "VEC3",
                                            {.normalized = true});
    addAnimation(builder, "", {sampler(times, values)}, {channel(0, 0, "translation")});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"animation 0, channel 0 animates translation with an output (accessor",
                 "not a VEC3 of floats"});
}

TEST(AnimationLoadTest, UnknownInterpolation) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
    addAnimation(builder, "", {sampler(times, values, "SMOOTH")}, {channel(0, 0, "scale")});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"animation 0, sampler 0 has an unknown interpolation ('SMOOTH'"});
}

TEST(AnimationLoadTest, WeightsOfANodeWithoutMorphTargetsWarn) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    addAnimation(builder, "", {sampler(times, values)}, {channel(0, 1, "weights")});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->animations[0].channels.empty());
    ASSERT_FALSE(scene->warnings.empty());
    EXPECT_NE(scene->warnings.back().find("animation 0, channel 0 animates the weights of node 1, "
                                          "which has no mesh with morph targets"),
              std::string::npos)
        << scene->warnings.back();
    expectError(loadGltf(builder, {.strict = true}), ErrorCode::InvalidFormat,
                {"animation 0, channel 0 animates the weights of node 1"});
}

TEST(AnimationLoadTest, ChannelsWithoutNodeAreIgnored) {
    auto builder = hierarchy();
    const auto times = builder.addAccessor(std::vector<float>{0, 1}, "SCALAR");
    const auto values = builder.addAccessor(std::vector<float>{0, 0, 0, 1, 1, 1}, "VEC3");
    addAnimation(builder, "", {sampler(times, values)},
                 {{{"sampler", 0}, {"target", {{"path", "pointer"}}}}});
    const auto scene = loadGltf(builder, {.strict = true});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->animations[0].channels.empty());
}

TEST(AnimationLoadTest, JointsOutsideTheNodeList) {
    auto builder = skinScene(true);
    builder.json()["skins"][0]["joints"] = {1, 9};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"skin 0 refers to node 9 (joint), but the asset has 3 nodes."});
}

TEST(AnimationLoadTest, JointIndexBeyondTheSkin) {
    expectError(loadGltf(skinScene(true, 2)), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0 has joint index 2 in JOINTS_0, but node 0 skins it with "
                 "skin 0, which has 2 joints."});
}

TEST(AnimationLoadTest, TooFewInverseBindMatrices) {
    auto builder = skinScene(true);
    builder.json()["skins"][0]["joints"] = {1, 2, 0};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"skin 0 has 3 joints but 2 inverse bind matrices"});
}

TEST(AnimationLoadTest, JointsMustBeUnsignedIntegers) {
    auto builder = skinScene(true);
    const auto floats = builder.addAccessor(std::vector<float>(12, 0.0f), "VEC4");
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = floats;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"JOINTS_0 holds joint indices"});
}

TEST(AnimationLoadTest, MorphTargetCountMustMatchTheVertexCount) {
    auto builder = morphScene();
    const auto shortDelta = builder.addAccessor(std::vector<float>{0, 0, 1, 0, 0, 1}, "VEC3");
    builder.json()["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = shortDelta;
    expectError(
        loadGltf(builder), ErrorCode::InvalidFormat,
        {"mesh 0, primitive 0, morph target 1 POSITION (accessor " + std::to_string(shortDelta) +
         ") has 2 elements, but the primitive has 3 "
         "vertices."});
}

TEST(AnimationLoadTest, MorphWeightCountsMustMatch) {
    expectError(loadGltf(morphScene(std::vector<float>{1.0f})), ErrorCode::InvalidFormat,
                {"mesh 0 has 1 default weights, but 2 morph targets."});
    expectError(loadGltf(morphScene({}, std::vector<float>{1, 2, 3})), ErrorCode::InvalidFormat,
                {"node 0 has 3 morph weights, but its mesh (0) has 2 morph targets."});
}

TEST(AnimationLoadTest, SparseMorphTargetWithoutBufferView) {
    auto builder = morphScene();
    // Target 1: all zeros except vertex 2 = (0, 0, 5), as a sparse accessor without a view.
    const auto indices = builder.addBufferView(std::vector<std::uint8_t>{2, 0, 0, 0});
    const float five[3] = {0, 0, 5};
    const auto values = builder.addBufferView(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(five), sizeof(five)));
    builder.json()["accessors"].push_back(
        {{"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"},
         {"sparse",
          {{"count", 1},
           {"indices", {{"bufferView", indices}, {"componentType", 5121}}},
           {"values", {{"bufferView", values}}}}}});
    const std::size_t sparse = builder.json()["accessors"].size() - 1;
    builder.json()["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] = sparse;
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto deltas = scene->readFloats(*scene->meshes[0].primitives[0].targets[1].position);
    ASSERT_EQ(deltas.size(), 3u);
    EXPECT_EQ(glm::vec3(deltas[0]), glm::vec3(0.0f));
    EXPECT_EQ(glm::vec3(deltas[2]), glm::vec3(0, 0, 5));
}

// Encore's time offset (extras.encoreTimeOffset): two animations with the same keys, one
// offset, play the same poses that far apart, clamped and looping.
TEST(AnimationLoadTest, TimeOffsetFromExtrasShiftsThePlayback) {
    auto builder = hierarchy();
    addSlide(builder, "plain");
    addSlide(builder, "offset");
    builder.json()["animations"][1]["extras"] = {{"encoreTimeOffset", 0.75},
                                                 {"somebodyElses", "kept out"}};
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->animations[0].timeOffset, 0.0f);
    EXPECT_EQ(scene->animations[1].timeOffset, 0.75f);
    EXPECT_EQ(scene->animations[1].end, 2.0f);  // The offset does not change the duration.

    AnimationPlayer plain(*scene), offset(*scene);
    ASSERT_TRUE(plain.select("plain").ok());
    ASSERT_TRUE(offset.select("offset").ok());
    for (PlaybackMode mode : {PlaybackMode::Clamp, PlaybackMode::Loop}) {
        plain.setMode(mode);
        offset.setMode(mode);
        for (double t : {-1.0, 0.0, 0.5, 1.1, 1.25, 1.9, 3.3}) {
            SCOPED_TRACE("t = " + std::to_string(t));
            offset.evaluate(t);
            // Looping, t + 0.75 wraps around the 2 s duration as a whole.
            const double shifted =
                mode == PlaybackMode::Loop ? std::fmod(t + 0.75 + 4.0, 2.0) : t + 0.75;
            plain.evaluate(shifted);
            expectMatrixNear(offset.instanceWorlds()[0], plain.instanceWorlds()[0], 1e-6f);
        }
    }
}

TEST(AnimationLoadTest, TimeOffsetThatIsNoNumberOrAbsurdIsRefused) {
    for (const json& bad : {json("soon"), json(1e7), json(-2e6)}) {
        auto builder = hierarchy();
        addSlide(builder, "a");
        builder.json()["animations"][0]["extras"] = {{"encoreTimeOffset", bad}};
        SCOPED_TRACE(bad.dump());
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"animation 0 extras", "encoreTimeOffset"});
    }
    // extras of any other type are somebody else's: ignored.
    auto builder = hierarchy();
    addSlide(builder, "a");
    builder.json()["animations"][0]["extras"] = json::array({1, 2});
    const auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->animations[0].timeOffset, 0.0f);
}

}  // namespace
}  // namespace encore::scene
