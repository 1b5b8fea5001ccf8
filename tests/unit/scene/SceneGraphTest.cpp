// Node hierarchy: local and world matrices, scene choice, instance order, instancing, bounds.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "SceneTestUtils.h"

namespace encore::scene {
namespace {

using testing::loadGltf;

bool near(const glm::mat4& a, const glm::mat4& b) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (std::abs(a[c][r] - b[c][r]) > 1e-5f) {
                return false;
            }
        }
    }
    return true;
}

// A builder with a triangle mesh 0 and no nodes.
test::GltfBuilder meshOnly() {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    builder.addMesh({.attributes = {{"POSITION", positions}}});
    return builder;
}

TEST(SceneGraphTest, TrsIsTranslateRotateScale) {
    auto builder = meshOnly();
    const glm::quat rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    builder.addScene({builder.addNode({.mesh = 0u,
                                       .translation = glm::vec3(10, 0, 0),
                                       .rotation = rotation,
                                       .scale = glm::vec3(2, 2, 2)})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const glm::mat4& world = scene->instances.at(0).world;
    // (1,0,0) scaled to (2,0,0), rotated to (0,2,0), translated to (10,2,0).
    const glm::vec4 point = world * glm::vec4(1, 0, 0, 1);
    EXPECT_NEAR(point.x, 10, 1e-5);
    EXPECT_NEAR(point.y, 2, 1e-5);
    EXPECT_NEAR(point.z, 0, 1e-5);
}

TEST(SceneGraphTest, MatrixAndHierarchy) {
    auto builder = meshOnly();
    const glm::mat4 parentMatrix = glm::translate(glm::mat4(1.0f), glm::vec3(0, 5, 0));
    const auto child = builder.addNode({.mesh = 0u, .scale = glm::vec3(3, 1, 1)});
    const auto parent = builder.addNode({.children = {child}, .matrix = parentMatrix});
    builder.addScene({parent});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), 1u);
    const glm::mat4 expected = parentMatrix * glm::scale(glm::mat4(1.0f), glm::vec3(3, 1, 1));
    EXPECT_TRUE(near(scene->instances[0].world, expected));
    EXPECT_TRUE(near(scene->nodes[child].world, expected));
    EXPECT_EQ(scene->nodes[child].parent.value, parent);
    EXPECT_TRUE(near(scene->nodes[parent].local, parentMatrix));
    // Normal matrix: inverse transpose of the upper 3x3.
    const glm::mat4 normal = glm::mat4(glm::transpose(glm::inverse(glm::mat3(expected))));
    EXPECT_TRUE(near(scene->instances[0].normalMatrix, normal));
    EXPECT_EQ(scene->bounds.min, glm::vec3(0, 5, 0));
    EXPECT_EQ(scene->bounds.max, glm::vec3(3, 6, 0));
}

TEST(SceneGraphTest, InstancesAreDepthFirst) {
    auto builder = meshOnly();
    const auto c = builder.addNode({.mesh = 0u, .name = "c"});
    const auto b = builder.addNode({.mesh = 0u, .children = {c}, .name = "b"});
    const auto d = builder.addNode({.mesh = 0u, .name = "d"});
    const auto a = builder.addNode({.mesh = 0u, .children = {b, d}, .name = "a"});
    builder.addScene({a});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    std::string order;
    for (const Instance& instance : scene->instances) {
        order += scene->nodes[instance.node.index()].name;
    }
    EXPECT_EQ(order, "abcd");
}

TEST(SceneGraphTest, SceneIndexChoosesTheScene) {
    auto builder = meshOnly();
    const auto first = builder.addNode({.mesh = 0u});
    const auto second = builder.addNode({.mesh = 0u});
    const auto third = builder.addNode({.mesh = 0u});
    builder.addScene({first});
    builder.addScene({second, third});
    builder.json()["scene"] = 1;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), 2u);
    EXPECT_EQ(scene->instances[0].node.value, second);

    builder.json().erase("scene");  // Without 'scene', scene 0 is drawn.
    scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok());
    ASSERT_EQ(scene->instances.size(), 1u);
    EXPECT_EQ(scene->instances[0].node.value, first);
}

TEST(SceneGraphTest, NoScenesDrawsEveryRootNode) {
    auto builder = meshOnly();
    const auto child = builder.addNode({.mesh = 0u});
    builder.addNode({.mesh = 0u, .children = {child}});
    builder.addNode({.mesh = 0u});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 3u);
    EXPECT_EQ(scene->instances[0].node.value, 1u);  // Root 1, its child 0, then root 2.
    EXPECT_EQ(scene->instances[1].node.value, 0u);
}

TEST(SceneGraphTest, MeshSharedByNodes) {
    auto builder = meshOnly();
    builder.addScene({builder.addNode({.mesh = 0u, .translation = glm::vec3(-5, 0, 0)}),
                      builder.addNode({.mesh = 0u, .translation = glm::vec3(5, 0, 0)})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 2u);
    EXPECT_EQ(scene->bounds.min.x, -5.0f);
    EXPECT_EQ(scene->bounds.max.x, 6.0f);
}

TEST(SceneGraphTest, GpuInstancing) {
    auto builder = meshOnly();
    const auto translations = builder.addAccessor(std::vector<float>{0, 0, 0, 10, 0, 0}, "VEC3");
    const auto scales = builder.addAccessor(std::vector<float>{1, 1, 1, 2, 2, 2}, "VEC3");
    const auto node = builder.addNode({.mesh = 0u, .translation = glm::vec3(0, 0, 1)});
    builder.json()["nodes"][node]["extensions"] = {
        {"EXT_mesh_gpu_instancing",
         {{"attributes", {{"TRANSLATION", translations}, {"SCALE", scales}}}}}};
    builder.json()["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    builder.json()["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    builder.addScene({node});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), 2u);
    const glm::vec4 corner = scene->instances[1].world * glm::vec4(1, 0, 0, 1);
    EXPECT_EQ(glm::vec3(corner), glm::vec3(12, 0, 1));
    EXPECT_EQ(scene->bounds.max, glm::vec3(12, 2, 1));
}

TEST(SceneGraphTest, GpuInstancingWithMismatchedCounts) {
    auto builder = meshOnly();
    const auto translations = builder.addAccessor(std::vector<float>{0, 0, 0, 10, 0, 0}, "VEC3");
    const auto scales = builder.addAccessor(std::vector<float>{1, 1, 1}, "VEC3");
    const auto node = builder.addNode({.mesh = 0u});
    builder.json()["nodes"][node]["extensions"] = {
        {"EXT_mesh_gpu_instancing",
         {{"attributes", {{"TRANSLATION", translations}, {"SCALE", scales}}}}}};
    builder.addScene({node});
    testing::expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                         {"node 0", "EXT_mesh_gpu_instancing", "different lengths"});
}

TEST(SceneGraphTest, ZeroScaleHasAFiniteNormalMatrix) {
    auto builder = meshOnly();
    builder.addScene({builder.addNode({.mesh = 0u, .scale = glm::vec3(1, 1, 0)})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const glm::mat4& normal = scene->instances[0].normalMatrix;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_TRUE(std::isfinite(normal[c][r]));
        }
    }
}

}  // namespace
}  // namespace encore::scene
