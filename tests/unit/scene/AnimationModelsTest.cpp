// The animation player on the shared sample models (../shared/models): Fox, BrainStem,
// CesiumMilkTruck and AnimatedMorphCube. Skips, saying so, when the models are absent.

#include <gtest/gtest.h>

#include <cmath>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "encore/scene/AnimationPlayer.h"

namespace encore::scene {
namespace {

std::optional<SceneData> loadModel(const std::string& relative) {
    const auto dir = test::sharedModelsDir();
    if (!dir || !std::filesystem::exists(*dir / relative)) {
        return std::nullopt;
    }
    auto scene = loadScene(*dir / relative);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    if (!scene.ok()) {
        return std::nullopt;
    }
    return std::move(*scene);
}

#define LOAD_OR_SKIP(variable, relative)                                            \
    auto variable = loadModel(relative);                                            \
    if (!variable) {                                                                \
        GTEST_SKIP() << "The shared sample model " << (relative)                    \
                     << " (../shared/models) is absent or did not load; skipping."; \
    }

float maxDifference(const glm::mat4& a, const glm::mat4& b) {
    float difference = 0.0f;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            difference = std::max(difference, std::abs(a[c][r] - b[c][r]));
        }
    }
    return difference;
}

// Joint matrices must be world(joint) * inverseBind of the player's own node worlds.
void expectJointsConsistent(const AnimationPlayer& player,
                            const SceneData& scene,
                            const std::string& label) {
    for (std::size_t s = 0; s < scene.skins.size(); ++s) {
        const Skin& skin = scene.skins[s];
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            const glm::mat4 expected =
                player.nodeWorlds()[skin.joints[j].index()] * skin.inverseBindMatrices[j];
            const glm::mat4& actual = player.jointMatrices()[player.skinJointOffsets()[s] + j];
            EXPECT_LT(maxDifference(actual, expected), 1e-5f) << label << " joint " << j;
            for (int c = 0; c < 4; ++c) {
                EXPECT_TRUE(
                    std::isfinite(actual[c][0] + actual[c][1] + actual[c][2] + actual[c][3]))
                    << label;
            }
        }
    }
}

TEST(AnimationModelsTest, FoxAnimationsAndBindPose) {
    LOAD_OR_SKIP(scene, "Fox/glTF-Binary/Fox.glb");
    ASSERT_EQ(scene->animations.size(), 3u);
    const std::pair<const char*, float> expected[] = {
        {"Survey", 3.41667f}, {"Walk", 0.708333f}, {"Run", 1.15833f}};
    for (std::size_t a = 0; a < 3; ++a) {
        EXPECT_EQ(scene->animations[a].name, expected[a].first);
        EXPECT_NEAR(scene->animations[a].end, expected[a].second, 1e-4f);
        EXPECT_EQ(scene->animations[a].channels.size(), 21u);
    }
    ASSERT_EQ(scene->skins.size(), 1u);
    EXPECT_EQ(scene->skins[0].joints.size(), 24u);
    ASSERT_EQ(scene->instances.size(), 1u);

    AnimationPlayer player(*scene);
    EXPECT_EQ(player.instanceRanges()[0].jointOffset, 0u);
    EXPECT_EQ(player.instanceRanges()[0].jointCount, 24u);
    // The rest pose is the bind pose: every joint matrix is the identity.
    for (const glm::mat4& joint : player.jointMatrices()) {
        EXPECT_LT(maxDifference(joint, glm::mat4(1.0f)), 1e-4f);
    }

    // At t = 0 each channel holds its first key: build the expected joint matrices by hand from
    // the rest pose, the first keys and the parent chain.
    ASSERT_TRUE(player.select("Survey").ok());
    player.evaluate(0.0);
    std::vector<glm::vec3> translation, scale;
    std::vector<glm::quat> rotation;
    for (const Node& node : scene->nodes) {
        translation.push_back(node.translation);
        rotation.push_back(node.rotation);
        scale.push_back(node.scale);
    }
    for (const AnimationChannel& channel : scene->animations[0].channels) {
        const AnimationSampler& sampler = scene->animations[0].samplers[channel.sampler];
        const float* v =
            sampler.values.data() +
            (sampler.interpolation == Interpolation::CubicSpline ? sampler.components : 0);
        const std::size_t n = channel.node.index();
        if (channel.path == AnimationPath::Translation) {
            translation[n] = glm::vec3(v[0], v[1], v[2]);
        }
        if (channel.path == AnimationPath::Rotation) {
            rotation[n] = glm::normalize(glm::quat(v[3], v[0], v[1], v[2]));
        }
        if (channel.path == AnimationPath::Scale) {
            scale[n] = glm::vec3(v[0], v[1], v[2]);
        }
    }
    auto world = [&](std::size_t n) {
        glm::mat4 result(1.0f);
        for (NodeId at(n); at.valid(); at = scene->nodes[at.index()].parent) {
            const Node& node = scene->nodes[at.index()];
            const glm::mat4 local =
                node.hasMatrix
                    ? node.local
                    : composeTrs(translation[at.index()], rotation[at.index()], scale[at.index()]);
            result = local * result;
        }
        return result;
    };
    const Skin& skin = scene->skins[0];
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const glm::mat4 expectedJoint = world(skin.joints[j].index()) * skin.inverseBindMatrices[j];
        EXPECT_LT(maxDifference(player.jointMatrices()[j], expectedJoint), 1e-4f) << "joint " << j;
    }
    expectJointsConsistent(player, *scene, "Fox Survey t=0");

    // Looping wraps each animation around its own end.
    ASSERT_TRUE(player.select("Walk").ok());
    player.evaluate(0.2);
    const std::vector<glm::mat4> reference(player.jointMatrices().begin(),
                                           player.jointMatrices().end());
    player.setMode(PlaybackMode::Loop);
    player.evaluate(0.2 + 3.0 * scene->animations[1].end);
    for (std::size_t j = 0; j < reference.size(); ++j) {
        EXPECT_LT(maxDifference(player.jointMatrices()[j], reference[j]), 1e-4f) << j;
    }
}

TEST(AnimationModelsTest, BrainStemJointsStayConsistent) {
    LOAD_OR_SKIP(scene, "BrainStem/glTF-Binary/BrainStem.glb");
    ASSERT_EQ(scene->animations.size(), 1u);
    EXPECT_NEAR(scene->animations[0].end, 34.88f, 1e-3f);
    ASSERT_EQ(scene->skins.size(), 1u);
    AnimationPlayer player(*scene);
    for (const double t : {0.0, 0.5, 3.3, 17.0, 34.88, 40.0, 1.0}) {
        player.evaluate(t);
        expectJointsConsistent(player, *scene, "BrainStem t=" + std::to_string(t));
    }
    // The Draco variant decodes to the same animation.
    LOAD_OR_SKIP(draco, "BrainStem/glTF-Draco/BrainStem.gltf");
    AnimationPlayer other(*draco);
    player.evaluate(12.5);
    other.evaluate(12.5);
    ASSERT_EQ(other.jointMatrices().size(), player.jointMatrices().size());
    for (std::size_t j = 0; j < player.jointMatrices().size(); ++j) {
        EXPECT_LT(maxDifference(player.jointMatrices()[j], other.jointMatrices()[j]), 1e-4f);
    }
}

TEST(AnimationModelsTest, CesiumMilkTruckTurnsOnlyItsWheels) {
    LOAD_OR_SKIP(scene, "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
    ASSERT_EQ(scene->animations.size(), 1u);
    EXPECT_EQ(scene->animations[0].name, "Wheels");
    EXPECT_NEAR(scene->animations[0].end, 1.25f, 1e-4f);
    ASSERT_EQ(scene->animations[0].channels.size(), 2u);
    AnimationPlayer player(*scene);
    player.evaluate(0.0);
    EXPECT_EQ(player.changedInstances().size(), scene->instances.size());
    player.evaluate(0.3);
    // Instances below a channel's node moved; the truck's body did not.
    std::vector<std::uint32_t> expected;
    for (std::size_t i = 0; i < scene->instances.size(); ++i) {
        bool below = false;
        for (NodeId at = scene->instances[i].node; at.valid() && !below;
             at = scene->nodes[at.index()].parent) {
            for (const AnimationChannel& channel : scene->animations[0].channels) {
                below = below || channel.node == at;
            }
        }
        if (below) {
            expected.push_back(static_cast<std::uint32_t>(i));
        } else {
            EXPECT_EQ(player.instanceWorlds()[i], scene->instances[i].world);
        }
    }
    EXPECT_EQ(expected.size(), 2u);
    EXPECT_EQ(std::vector<std::uint32_t>(player.changedInstances().begin(),
                                         player.changedInstances().end()),
              expected);
    for (const std::uint32_t i : expected) {
        EXPECT_GT(maxDifference(player.instanceWorlds()[i], scene->instances[i].world), 1e-3f);
        // A wheel turns about its axle: its world position stays.
        EXPECT_LT(glm::length(glm::vec3(player.instanceWorlds()[i][3]) -
                              glm::vec3(scene->instances[i].world[3])),
                  1e-4f);
        EXPECT_LT(maxDifference(player.instanceNormalMatrices()[i],
                                normalMatrixOf(player.instanceWorlds()[i])),
                  1e-6f);
    }
}

TEST(AnimationModelsTest, AnimatedMorphCubeWeights) {
    LOAD_OR_SKIP(scene, "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb");
    ASSERT_EQ(scene->meshes.size(), 1u);
    ASSERT_EQ(scene->meshes[0].weights.size(), 2u);
    for (const Primitive& primitive : scene->meshes[0].primitives) {
        ASSERT_EQ(primitive.targets.size(), 2u);
        EXPECT_TRUE(primitive.targets[0].position && primitive.targets[0].normal);
        EXPECT_EQ(scene->accessors[primitive.targets[0].position->index()].count,
                  primitive.vertexCount);
    }
    ASSERT_EQ(scene->animations.size(), 1u);
    const Animation& animation = scene->animations[0];
    EXPECT_EQ(animation.name, "Square");
    EXPECT_NEAR(animation.end, 4.2f, 1e-4f);
    const AnimationSampler& sampler = animation.samplers[animation.channels[0].sampler];
    ASSERT_EQ(sampler.interpolation, Interpolation::Linear);
    ASSERT_EQ(sampler.components, 2u);

    AnimationPlayer player(*scene);
    ASSERT_EQ(player.morphWeights().size(), 2u);
    EXPECT_EQ(player.instanceRanges()[0].weightOffset, 0u);
    // Exactly on key 40: its values; halfway between keys 40 and 41: their mean.
    const std::size_t k = 40;
    player.evaluate(sampler.times[k]);
    EXPECT_FLOAT_EQ(player.morphWeights()[0], sampler.values[k * 2]);
    EXPECT_FLOAT_EQ(player.morphWeights()[1], sampler.values[k * 2 + 1]);
    player.evaluate(0.5 * (double(sampler.times[k]) + sampler.times[k + 1]));
    for (int w = 0; w < 2; ++w) {
        EXPECT_NEAR(player.morphWeights()[w],
                    0.5f * (sampler.values[k * 2 + w] + sampler.values[(k + 1) * 2 + w]), 1e-6f);
    }
    EXPECT_EQ(player.changedInstances().size(), 1u);

    // The quantised variant (normalised integer weights and deltas) plays the same within
    // its quantisation step.
    LOAD_OR_SKIP(quantized, "AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf");
    AnimationPlayer other(*quantized);
    for (const double t : {0.0, 0.7, 1.5, 2.25, 3.9, 5.0}) {
        player.evaluate(t);
        other.evaluate(t);
        for (int w = 0; w < 2; ++w) {
            EXPECT_NEAR(player.morphWeights()[w], other.morphWeights()[w], 0.01f) << t;
        }
    }
}

}  // namespace
}  // namespace encore::scene
