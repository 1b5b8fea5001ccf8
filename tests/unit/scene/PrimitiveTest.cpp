// Primitive conversion: topologies, line loop and triangle fan rewriting, flat and zero normals.

#include <gtest/gtest.h>

#include "SceneTestUtils.h"

namespace encore::scene {
namespace {

using testing::loadGltf;

// The unit quad (0,0) (1,0) (1,1) (0,1) drawn with `mode`, optional indices and normals.
test::GltfBuilder quadBuilder(std::uint32_t mode,
                              std::optional<std::vector<std::uint16_t>> indices = {},
                              bool withNormals = true) {
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.mode = mode;
    primitive.attributes["POSITION"] =
        builder.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    if (withNormals) {
        primitive.attributes["NORMAL"] =
            builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    }
    if (indices) {
        primitive.indices = builder.addIndices(*indices);
    }
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    return builder;
}

const Primitive& loadPrimitive(const Result<SceneData>& scene) {
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene->meshes.at(0).primitives.at(0);
}

TEST(PrimitiveTest, TopologiesMapDirectly) {
    const std::pair<std::uint32_t, Topology> cases[] = {{0, Topology::PointList},
                                                        {1, Topology::LineList},
                                                        {3, Topology::LineStrip},
                                                        {4, Topology::TriangleList},
                                                        {5, Topology::TriangleStrip}};
    for (const auto& [mode, topology] : cases) {
        auto scene = loadGltf(quadBuilder(mode));
        const Primitive& primitive = loadPrimitive(scene);
        EXPECT_EQ(primitive.topology, topology) << mode;
        EXPECT_FALSE(primitive.indices) << mode;
        EXPECT_EQ(primitive.vertexCount, 4u);
    }
}

TEST(PrimitiveTest, LineLoopWithoutIndicesBecomesClosedStrip) {
    auto scene = loadGltf(quadBuilder(2));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.topology, Topology::LineStrip);
    ASSERT_TRUE(primitive.indices);
    EXPECT_EQ(scene->readIndices(*primitive.indices), (std::vector<std::uint32_t>{0, 1, 2, 3, 0}));
    EXPECT_EQ(scene->accessors[primitive.indices->index()].componentType, ComponentType::Uint16);
}

TEST(PrimitiveTest, IndexedLineLoopAppendsItsFirstIndex) {
    auto scene = loadGltf(quadBuilder(2, std::vector<std::uint16_t>{3, 2, 1}));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(scene->readIndices(*primitive.indices), (std::vector<std::uint32_t>{3, 2, 1, 3}));
}

TEST(PrimitiveTest, TriangleFanBecomesTriangleList) {
    auto scene = loadGltf(quadBuilder(6));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.topology, Topology::TriangleList);
    EXPECT_EQ(scene->readIndices(*primitive.indices),
              (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(PrimitiveTest, IndexedTriangleFan) {
    // The converter's triangles, in the fan's order (mesh optimisation would reorder them).
    LoadOptions options;
    options.optimizeMeshes = false;
    options.buildLevelsOfDetail = false;
    auto scene = loadGltf(quadBuilder(6, std::vector<std::uint16_t>{3, 0, 1, 2}), options);
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(scene->readIndices(*primitive.indices),
              (std::vector<std::uint32_t>{3, 0, 1, 3, 1, 2}));
}

TEST(PrimitiveTest, FlatNormalsDeindexTriangles) {
    auto scene = loadGltf(quadBuilder(4, std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3}, false));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.topology, Topology::TriangleList);
    EXPECT_FALSE(primitive.indices);
    EXPECT_EQ(primitive.vertexCount, 6u);
    const auto positions = scene->readFloats(*primitive.attribute(Semantic::Position));
    const auto normals = scene->readFloats(*primitive.attribute(Semantic::Normal));
    ASSERT_EQ(positions.size(), 6u);
    ASSERT_EQ(normals.size(), 6u);
    EXPECT_EQ(glm::vec3(positions[4]), glm::vec3(1, 1, 0));
    EXPECT_EQ(glm::vec3(positions[5]), glm::vec3(0, 1, 0));
    for (const auto& normal : normals) {
        EXPECT_EQ(glm::vec3(normal), glm::vec3(0, 0, 1));
    }
    // Sorted by semantic, Position first.
    EXPECT_EQ(primitive.attributes.front().semantic, Semantic::Position);
    EXPECT_EQ(primitive.attributes[1].semantic, Semantic::Normal);
}

TEST(PrimitiveTest, FlatNormalsOfAStripKeepTheWinding) {
    auto scene = loadGltf(quadBuilder(5, std::nullopt, false));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.topology, Topology::TriangleList);
    EXPECT_EQ(primitive.vertexCount, 6u);
    const auto normals = scene->readFloats(*primitive.attribute(Semantic::Normal));
    // Strip (0,1,2) then (2,1,3): the second triangle of this strip is folded back, its
    // winding-corrected normal faces -z.
    EXPECT_EQ(glm::vec3(normals[0]), glm::vec3(0, 0, 1));
    EXPECT_EQ(glm::vec3(normals[3]), glm::vec3(0, 0, -1));
}

TEST(PrimitiveTest, FlatNormalsOfAFan) {
    auto scene = loadGltf(quadBuilder(6, std::nullopt, false));
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.vertexCount, 6u);
    for (const auto& normal : scene->readFloats(*primitive.attribute(Semantic::Normal))) {
        EXPECT_EQ(glm::vec3(normal), glm::vec3(0, 0, 1));
    }
}

TEST(PrimitiveTest, PointsAndLinesGetZeroNormals) {
    for (std::uint32_t mode : {0u, 1u, 2u, 3u}) {
        auto scene = loadGltf(quadBuilder(mode, std::nullopt, false));
        const Primitive& primitive = loadPrimitive(scene);
        const auto normal = primitive.attribute(Semantic::Normal);
        ASSERT_TRUE(normal) << mode;
        const Accessor& accessor = scene->accessors[normal->index()];
        EXPECT_EQ(accessor.componentType, ComponentType::Float32);
        EXPECT_EQ(accessor.componentCount, 3);
        EXPECT_EQ(accessor.count, 4u);
        for (const auto& value : scene->readFloats(*normal)) {
            EXPECT_EQ(glm::vec3(value), glm::vec3(0));
        }
    }
}

TEST(PrimitiveTest, BoundsComeFromPositions) {
    auto builder = quadBuilder(4);
    builder.json()["accessors"][0].erase("min");  // Computed when min/max are absent.
    auto scene = loadGltf(builder);
    const Primitive& primitive = loadPrimitive(scene);
    EXPECT_EQ(primitive.bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(primitive.bounds.max, glm::vec3(1, 1, 0));
}

TEST(PrimitiveTest, UnknownAttributesAreSkipped) {
    auto builder = quadBuilder(4);
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["_CUSTOM"] = 1;
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_3"] = 1;
    auto scene = loadGltf(builder);
    EXPECT_EQ(loadPrimitive(scene).attributes.size(), 2u);
}

}  // namespace
}  // namespace encore::scene
