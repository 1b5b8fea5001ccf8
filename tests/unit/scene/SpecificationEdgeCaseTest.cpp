// What the glTF specification settles for unusual but possible input: primitives without
// POSITION are skipped, primitive-restart values in indices are warned about (and strips drawn
// as the indices say), empty meshes, scenes and files get clear messages, non-finite transforms
// keep bounds finite and NaN out of normal matrices, and deep JSON or node hierarchies never
// overflow the stack.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>

#include "SceneTestUtils.h"

namespace encore::scene {
namespace {

using testing::expectError;
using testing::loadGlb;
using testing::loadGltf;
using testing::loadText;

bool hasWarning(const SceneData& scene, const std::string& fragment) {
    for (const std::string& warning : scene.warnings) {
        if (warning.find(fragment) != std::string::npos) {
            return true;
        }
    }
    return false;
}

std::string describeWarnings(const SceneData& scene) {
    std::string text;
    for (const std::string& warning : scene.warnings) {
        text += "\n  " + warning;
    }
    return text.empty() ? " (none)" : text;
}

bool isFinite(const glm::mat4& matrix) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(matrix[c][r])) {
                return false;
            }
        }
    }
    return true;
}

bool isFinite(const Bounds& bounds) {
    return std::isfinite(bounds.min.x) && std::isfinite(bounds.min.y) &&
           std::isfinite(bounds.min.z) && std::isfinite(bounds.max.x) &&
           std::isfinite(bounds.max.y) && std::isfinite(bounds.max.z);
}

std::uint32_t addTriangleMesh(test::GltfBuilder& builder) {
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    return builder.addMesh({.attributes = {{"POSITION", positions}}});
}

// ---- Primitives without POSITION -----------------------------------------------------------

TEST(SpecificationEdgeCaseTest, PrimitiveWithoutPositionIsSkippedWithAWarning) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const auto mesh = builder.addMesh(std::vector<test::GltfBuilder::PrimitiveDesc>{
        {.attributes = {{"NORMAL", normals}}}, {.attributes = {{"POSITION", positions}}}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    EXPECT_EQ(scene->meshes[0].primitives.size(), 1u);
    EXPECT_EQ(scene->instances.size(), 1u);
    EXPECT_TRUE(hasWarning(*scene, "mesh 0, primitive 0 has no POSITION attribute"))
        << describeWarnings(*scene);
    EXPECT_FALSE(scene->bounds.empty());
}

TEST(SpecificationEdgeCaseTest, PrimitiveWithoutAttributesIsSkipped) {
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    builder.json()["meshes"][mesh]["primitives"].push_back(
        {{"attributes", nlohmann::json::object()}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->meshes[0].primitives.size(), 1u);
    EXPECT_TRUE(hasWarning(*scene, "mesh 0, primitive 1 has no POSITION"))
        << describeWarnings(*scene);
}

// ---- Primitive-restart values --------------------------------------------------------------

// POSITION and NORMAL (so the indices are kept: without normals they are de-indexed).
std::map<std::string, std::uint32_t> manyVertices(test::GltfBuilder& builder, std::size_t count) {
    std::vector<glm::vec3> positions(count);
    for (std::size_t i = 0; i < count; ++i) {
        positions[i] = glm::vec3(float(i % 7), float(i % 5), 0.0f);
    }
    const std::vector<glm::vec3> normals(count, glm::vec3(0, 0, 1));
    return {{"POSITION", builder.addPositions(positions)}, {"NORMAL", builder.addNormals(normals)}};
}

TEST(SpecificationEdgeCaseTest, SixteenBitRestartValueInAStripIsWarnedAndWidened) {
    test::GltfBuilder builder;
    const auto vertices = manyVertices(builder, 65537);
    const auto indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 0xFFFF, 2, 3});
    const auto mesh = builder.addMesh({.attributes = vertices, .indices = indices, .mode = 5});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(hasWarning(*scene, "primitive-restart value 65535")) << describeWarnings(*scene);
    EXPECT_TRUE(hasWarning(*scene, "position 2")) << describeWarnings(*scene);
    const Primitive& primitive = scene->meshes[0].primitives[0];
    ASSERT_TRUE(primitive.indices.has_value());
    EXPECT_EQ(primitive.topology, Topology::TriangleStrip);
    EXPECT_EQ(scene->accessors[primitive.indices->index()].componentType, ComponentType::Uint32);
    EXPECT_EQ(scene->readIndices(*primitive.indices),
              (std::vector<std::uint32_t>{0, 1, 0xFFFF, 2, 3}));
}

TEST(SpecificationEdgeCaseTest, SixteenBitRestartValueInAListKeepsItsIndices) {
    test::GltfBuilder builder;
    const auto vertices = manyVertices(builder, 65537);
    const auto indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 0xFFFF});
    const auto mesh = builder.addMesh({.attributes = vertices, .indices = indices});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(hasWarning(*scene, "primitive-restart value 65535")) << describeWarnings(*scene);
    // List topologies never restart, so the data may stay as it is.
    const Primitive& primitive = scene->meshes[0].primitives[0];
    EXPECT_EQ(scene->readIndices(*primitive.indices), (std::vector<std::uint32_t>{0, 1, 0xFFFF}));
}

TEST(SpecificationEdgeCaseTest, EightBitRestartValueIsWarnedAndWidenedToSixteenBits) {
    test::GltfBuilder builder;
    const auto vertices = manyVertices(builder, 256);
    const auto indices = builder.addIndices(std::vector<std::uint8_t>{0, 1, 0xFF, 2});
    const auto mesh = builder.addMesh({.attributes = vertices, .indices = indices, .mode = 5});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(hasWarning(*scene, "primitive-restart value 255")) << describeWarnings(*scene);
    const Primitive& primitive = scene->meshes[0].primitives[0];
    EXPECT_EQ(scene->accessors[primitive.indices->index()].componentType, ComponentType::Uint16);
    EXPECT_EQ(scene->readIndices(*primitive.indices), (std::vector<std::uint32_t>{0, 1, 0xFF, 2}));
}

TEST(SpecificationEdgeCaseTest, RestartValueIsAnErrorWhenStrict) {
    test::GltfBuilder builder;
    const auto vertices = manyVertices(builder, 256);
    const auto indices = builder.addIndices(std::vector<std::uint8_t>{0, 1, 0xFF});
    const auto mesh = builder.addMesh({.attributes = vertices, .indices = indices});
    builder.addScene({builder.addNode({.mesh = mesh})});
    expectError(loadGlb(builder, {.strict = true}), ErrorCode::InvalidFormat,
                {"test.glb: ", "mesh 0, primitive 0", "primitive-restart value 255"});
}

// ---- Empty things --------------------------------------------------------------------------

TEST(SpecificationEdgeCaseTest, AccessorWithCountZeroIsAClearError) {
    auto builder = testing::triangleBuilder();
    builder.json()["accessors"][0]["count"] = 0;
    builder.json()["accessors"][0].erase("min");
    builder.json()["accessors"][0].erase("max");
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"test.gltf: ", "accessor 0 (POSITION of mesh 0, primitive 0)", "count 0"});
}

// Issue 32: a triangle fan of two indices has no triangle. Its rewritten index accessor has
// count 0 in a new, empty buffer (data() null), which every copy of its bytes must accept.
TEST(SpecificationEdgeCaseTest, FanWithoutTrianglesHasAnEmptyIndexAccessor) {
    auto scene = loadGltf(test::fanWithoutTriangles());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->meshes.size(), 1u);
    ASSERT_EQ(scene->meshes[0].primitives.size(), 1u);
    const Primitive& primitive = scene->meshes[0].primitives[0];
    ASSERT_TRUE(primitive.indices);
    const Accessor& accessor = scene->accessors[primitive.indices->index()];
    EXPECT_EQ(accessor.count, 0u);
    EXPECT_EQ(scene->bufferViews[accessor.view.index()].byteLength, 0u);
    EXPECT_TRUE(
        scene->buffers[scene->bufferViews[accessor.view.index()].buffer.index()].bytes.empty());
    EXPECT_TRUE(scene->readIndices(*primitive.indices).empty());
    EXPECT_TRUE(scene->packedAccessorBytes(*primitive.indices).empty());
}

// A buffer of byteLength 0 (an empty data: uri) and a bufferView of byteLength 0 into it.
test::GltfBuilder triangleWithEmptyBuffer() {
    auto builder = testing::triangleBuilder();
    builder.json()["buffers"].push_back(
        {{"byteLength", 0}, {"uri", "data:application/octet-stream;base64,"}});
    builder.json()["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 0}});
    return builder;
}

TEST(SpecificationEdgeCaseTest, EmptyBufferAndViewLoad) {
    auto scene = loadGltf(triangleWithEmptyBuffer());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->meshes.size(), 1u);
    const bool emptyView =
        std::any_of(scene->bufferViews.begin(), scene->bufferViews.end(), [&](const auto& view) {
            return view.byteLength == 0 && scene->buffers[view.buffer.index()].bytes.empty();
        });
    EXPECT_TRUE(emptyView);
}

TEST(SpecificationEdgeCaseTest, AccessorInAnEmptyViewIsAClearError) {
    auto builder = triangleWithEmptyBuffer();
    builder.json()["accessors"][0]["bufferView"] = builder.json()["bufferViews"].size() - 1;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"test.gltf: ", "accessor 0 (POSITION of mesh 0, primitive 0)",
                 "reads past the end of bufferView 1", "length 0"});
}

TEST(SpecificationEdgeCaseTest, IndexAccessorWithCountZeroIsAClearError) {
    auto builder = testing::triangleBuilder();
    const auto indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 2});
    builder.json()["meshes"][0]["primitives"][0]["indices"] = indices;
    builder.json()["accessors"][indices]["count"] = 0;
    builder.json()["accessors"][indices]["min"] = {2147483647};
    builder.json()["accessors"][indices]["max"] = {2147483647};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"test.gltf: ", "count 0"});
}

TEST(SpecificationEdgeCaseTest, MeshWithoutPrimitivesIsWarnedAbout) {
    test::GltfBuilder builder;
    builder.json()["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array()}}});
    builder.addScene({builder.addNode({.mesh = 0})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->meshes[0].primitives.empty());
    EXPECT_TRUE(hasWarning(*scene, "mesh 0 has no primitives")) << describeWarnings(*scene);
    EXPECT_TRUE(scene->bounds.empty());
}

TEST(SpecificationEdgeCaseTest, NodesWithoutMeshesDrawNothingWithAWarning) {
    test::GltfBuilder builder;
    const auto child = builder.addNode({.name = "child"});
    builder.addScene({builder.addNode({.children = {child}})});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->instances.empty());
    EXPECT_TRUE(scene->bounds.empty());
    EXPECT_TRUE(hasWarning(*scene, "draws nothing")) << describeWarnings(*scene);
    EXPECT_TRUE(hasWarning(*scene, "no node of the scene")) << describeWarnings(*scene);
}

TEST(SpecificationEdgeCaseTest, SceneWithoutNodesDrawsNothingWithAWarning) {
    test::GltfBuilder builder;
    addTriangleMesh(builder);
    builder.json()["scenes"] = nlohmann::json::array({nlohmann::json::object()});
    builder.json()["scene"] = 0;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->instances.empty());
    EXPECT_TRUE(hasWarning(*scene, "the scene it shows has no nodes")) << describeWarnings(*scene);
}

TEST(SpecificationEdgeCaseTest, EmptySceneIsNotAnErrorWhenStrict) {
    auto scene = loadSceneFromMemory(std::vector<std::uint8_t>{}, "/nonexistent", "empty.gltf", {});
    EXPECT_FALSE(scene.ok());
    const std::string minimal = R"({"asset": {"version": "2.0"}})";
    auto loaded = loadSceneFromMemory(std::vector<std::uint8_t>(minimal.begin(), minimal.end()),
                                      "/nonexistent", "minimal.gltf", {.strict = true});
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_TRUE(loaded->instances.empty());
    EXPECT_TRUE(hasWarning(*loaded, "no scenes and no nodes")) << describeWarnings(*loaded);
}

TEST(SpecificationEdgeCaseTest, EmptyFileIsAClearError) {
    expectError(loadText(""), ErrorCode::InvalidFormat, {"test.gltf: ", "empty", "0 bytes"});
    expectError(loadText(std::string("\xEF\xBB\xBF", 3)), ErrorCode::InvalidFormat,
                {"test.gltf: ", "empty"});
    auto glb = loadText("", "test.glb");
    ASSERT_FALSE(glb.ok());
    EXPECT_NE(glb.error().message.find("test.glb: "), std::string::npos) << glb.error().message;
}

// ---- Non-finite and degenerate transforms --------------------------------------------------

TEST(SpecificationEdgeCaseTest, InfiniteMatrixIsNotDrawnAndBoundsStayFinite) {
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    const auto good = builder.addNode({.mesh = mesh});
    const auto bad = builder.addNode({.mesh = mesh});
    // 1e39 is a valid JSON number but no float: it becomes infinity.
    builder.json()["nodes"][bad]["matrix"] = {1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    builder.addScene({good, bad});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 1u);
    EXPECT_TRUE(hasWarning(*scene, "node 1 has a world transform with values that are not finite"))
        << describeWarnings(*scene);
    ASSERT_FALSE(scene->bounds.empty());
    EXPECT_TRUE(isFinite(scene->bounds));
    EXPECT_EQ(scene->bounds.max, glm::vec3(1, 1, 0));
}

TEST(SpecificationEdgeCaseTest, InfiniteTranslationAndScaleAreNotDrawn) {
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    const auto a = builder.addNode({.mesh = mesh});
    const auto b = builder.addNode({.mesh = mesh});
    builder.json()["nodes"][a]["translation"] = {0, -1e39, 0};
    builder.json()["nodes"][b]["scale"] = {1e39, 1, 1};
    builder.json()["nodes"][b]["rotation"] = {0, 0.7071068, 0, 0.7071068};
    builder.addScene({a, b});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->instances.empty());
    EXPECT_TRUE(scene->bounds.empty());
    EXPECT_TRUE(hasWarning(*scene, "node 0 has a world transform")) << describeWarnings(*scene);
    EXPECT_TRUE(hasWarning(*scene, "node 1 has a world transform")) << describeWarnings(*scene);
}

TEST(SpecificationEdgeCaseTest, NonFiniteTransformIsAnErrorWhenStrict) {
    test::GltfBuilder builder;
    const auto node = builder.addNode({.mesh = addTriangleMesh(builder)});
    builder.json()["nodes"][node]["translation"] = {1e39, 0, 0};
    builder.addScene({node});
    expectError(loadGltf(builder, {.strict = true}), ErrorCode::InvalidFormat,
                {"test.gltf: ", "node 0", "not finite"});
}

TEST(SpecificationEdgeCaseTest, NaNPositionsAreLeftOutOfTheBounds) {
    test::GltfBuilder builder;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    // No min/max: the bounds come from the values themselves.
    const auto positions =
        builder.addAccessor(std::vector<float>{0, 0, 0, nan, 5, 0, 2, 1, 0, inf, 0, 0}, "VEC3");
    const auto mesh = builder.addMesh(
        {.attributes = {{"POSITION", positions}},
         .indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3})});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_FALSE(scene->bounds.empty());
    EXPECT_TRUE(isFinite(scene->bounds));
    EXPECT_EQ(scene->bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(scene->bounds.max, glm::vec3(2, 1, 0));
    for (const Instance& instance : scene->instances) {
        EXPECT_TRUE(isFinite(instance.normalMatrix));
    }
}

TEST(SpecificationEdgeCaseTest, NonFiniteMinMaxFallsBackToTheValues) {
    auto builder = testing::triangleBuilder();
    builder.json()["accessors"][0]["min"] = {0, 0, -1e39};
    builder.json()["accessors"][0]["max"] = {1, 1, 0};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(isFinite(scene->bounds));
    EXPECT_EQ(scene->bounds.min, glm::vec3(0, 0, 0));
}

TEST(SpecificationEdgeCaseTest, NormalMatricesOfSingularTransformsAreFinite) {
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    std::vector<std::uint32_t> nodes;
    nodes.push_back(builder.addNode({.mesh = mesh, .scale = glm::vec3(0, 1, 1)}));
    nodes.push_back(builder.addNode({.mesh = mesh, .scale = glm::vec3(0, 0, 1)}));
    nodes.push_back(builder.addNode({.mesh = mesh, .scale = glm::vec3(0, 0, 0)}));
    nodes.push_back(builder.addNode({.mesh = mesh, .matrix = glm::mat4(0.0f)}));
    // Rank two without a zero scale: every column lies in the plane x = y.
    glm::mat4 sheared(1.0f);
    sheared[0] = glm::vec4(1, 1, 0, 0);
    sheared[1] = glm::vec4(2, 2, 0, 0);
    nodes.push_back(builder.addNode({.mesh = mesh, .matrix = sheared}));
    nodes.push_back(builder.addNode({.mesh = mesh, .scale = glm::vec3(1e-30f, 1e-30f, 1e-30f)}));
    builder.addScene(nodes);
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), nodes.size());
    for (const Instance& instance : scene->instances) {
        EXPECT_TRUE(isFinite(instance.normalMatrix)) << "node " << instance.node.value;
        EXPECT_TRUE(isFinite(instance.world)) << "node " << instance.node.value;
        const glm::mat3 normal(instance.normalMatrix);
        EXPECT_FALSE(normal[0] == glm::vec3(0) && normal[1] == glm::vec3(0) &&
                     normal[2] == glm::vec3(0))
            << "node " << instance.node.value << " has a zero normal matrix";
    }
    // A zero x scale flattens the mesh onto x = 0: its normals all point along x.
    const glm::mat3 flat(scene->instances[0].normalMatrix);
    const glm::vec3 normal = flat * glm::vec3(0, 0, 1);
    EXPECT_TRUE(std::isfinite(normal.x));
    EXPECT_TRUE(isFinite(scene->bounds));
}

TEST(SpecificationEdgeCaseTest, NonFiniteInstanceTransformsAreNotDrawn) {
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const auto translations =
        builder.addAccessor(std::vector<float>{0, 0, 0, nan, 0, 0, 5, 0, 0}, "VEC3");
    const auto node = builder.addNode({.mesh = mesh});
    builder.json()["nodes"][node]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]
                  ["TRANSLATION"] = translations;
    builder.json()["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    builder.addScene({node});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 2u);
    EXPECT_TRUE(hasWarning(*scene, "node 0 (instance 1)")) << describeWarnings(*scene);
    EXPECT_TRUE(isFinite(scene->bounds));
    EXPECT_EQ(scene->bounds.max, glm::vec3(6, 1, 0));
}

TEST(SpecificationEdgeCaseTest, BoundsIgnoreNonFinitePoints) {
    Bounds bounds;
    bounds.extend(glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0, 0));
    bounds.extend(glm::vec3(0, std::numeric_limits<float>::infinity(), 0));
    EXPECT_TRUE(bounds.empty());
    bounds.extend(glm::vec3(1, 2, 3));
    glm::mat4 infinite(1.0f);
    infinite[3].x = std::numeric_limits<float>::infinity();
    EXPECT_TRUE(bounds.transformed(infinite).empty());
    EXPECT_EQ(bounds.min, glm::vec3(1, 2, 3));
    EXPECT_EQ(bounds.max, glm::vec3(1, 2, 3));
}

// ---- Deep JSON and deep or cyclic hierarchies ----------------------------------------------

TEST(SpecificationEdgeCaseTest, JsonNestedTwoHundredThousandLevelsIsRefusedWithoutOverflow) {
    constexpr std::size_t kDepth = 200000;
    std::string text = R"({"asset": {"version": "2.0"}, "extras": )";
    text += std::string(kDepth, '[') + std::string(kDepth, ']') + "}";
    expectError(loadText(text), ErrorCode::LimitExceeded, {"test.gltf: ", "nests", "512"});
    std::string objects = R"({"asset": {"version": "2.0"}, "extras": )";
    for (std::size_t i = 0; i < kDepth; ++i) {
        objects += R"({"a":)";
    }
    objects += "0" + std::string(kDepth, '}') + "}";
    expectError(loadText(objects), ErrorCode::LimitExceeded, {"nests"});
}

TEST(SpecificationEdgeCaseTest, BracketsInsideStringsDoNotCountAsNesting) {
    auto builder = testing::triangleBuilder();
    builder.json()["nodes"][0]["name"] = std::string(100000, '[') + "\\\"" + std::string(10, '{');
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 1u);
}

TEST(SpecificationEdgeCaseTest, ModerateJsonNestingInExtrasIsAccepted) {
    auto builder = testing::triangleBuilder();
    nlohmann::json extras = 1;
    for (int i = 0; i < 400; ++i) {
        extras = nlohmann::json::array({extras});
    }
    builder.json()["extras"] = extras;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
}

TEST(SpecificationEdgeCaseTest, NodeChainTwoHundredThousandDeepLoadsIteratively) {
    constexpr std::uint32_t kDepth = 200000;
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    // Node i's child is node i + 1; each moves its subtree up by 1, the last holds the mesh.
    nlohmann::json nodes = nlohmann::json::array();
    for (std::uint32_t i = 0; i < kDepth; ++i) {
        nlohmann::json node = {{"translation", {0, 1, 0}}};
        if (i + 1 < kDepth) {
            node["children"] = {i + 1};
        } else {
            node["mesh"] = mesh;
        }
        nodes.push_back(std::move(node));
    }
    builder.json()["nodes"] = std::move(nodes);
    builder.addScene({0});
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->instances.size(), 1u);
    EXPECT_FLOAT_EQ(scene->instances[0].world[3].y, float(kDepth));
    EXPECT_EQ(scene->nodes[kDepth - 1].parent.value, kDepth - 2);
}

TEST(SpecificationEdgeCaseTest, LongNodeCycleIsRefusedWithoutOverflow) {
    constexpr std::uint32_t kLength = 200000;
    test::GltfBuilder builder;
    const auto mesh = addTriangleMesh(builder);
    nlohmann::json nodes = nlohmann::json::array();
    for (std::uint32_t i = 0; i < kLength; ++i) {
        nodes.push_back({{"children", {(i + 1) % kLength}}, {"mesh", mesh}});
    }
    builder.json()["nodes"] = std::move(nodes);
    builder.json()["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    builder.json()["scene"] = 0;
    expectError(loadGlb(builder), ErrorCode::InvalidFormat, {"test.glb: ", "cycle"});
}

}  // namespace
}  // namespace encore::scene
