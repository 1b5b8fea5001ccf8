// Clusters (meshlets) built at load (MeshOptimizer.h): reordering a level into clusters keeps
// exactly its triangles, each with its corners in order; the clusters of every level cover each
// of its triangles once, in runs of at most 256, each inside its cluster's sphere; the cone says
// "facing away" only where every triangle of the cluster faces away; blending primitives, loads
// without mesh optimisation and with LoadOptions::buildClusters off get none, and so do scenes
// drawing fewer triangles than LoadOptions::clustersFromTriangles.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <string>

#include "SceneTestUtils.h"
#include "scene/MeshOptimizer.h"

namespace encore::scene {
namespace {

using testing::loadGlb;

struct Sphere {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;  // Triangles in random order, counter-clockwise outside.
};

Sphere uvSphere(std::uint32_t rings, std::uint32_t segments) {
    Sphere sphere;
    for (std::uint32_t r = 0; r <= rings; ++r) {
        for (std::uint32_t s = 0; s <= segments; ++s) {
            const float theta = 3.14159265f * float(r) / float(rings);
            const float phi = 6.2831853f * float(s) / float(segments);
            sphere.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                        std::sin(theta) * std::sin(phi)});
        }
    }
    std::vector<std::array<std::uint32_t, 3>> triangles;
    const std::uint32_t row = segments + 1;
    for (std::uint32_t r = 0; r < rings; ++r) {
        for (std::uint32_t s = 0; s < segments; ++s) {
            const std::uint32_t a = r * row + s, b = a + row;
            triangles.push_back({a, a + 1, b});
            triangles.push_back({a + 1, b + 1, b});
        }
    }
    std::mt19937 random(11);
    std::shuffle(triangles.begin(), triangles.end(), random);
    for (const auto& triangle : triangles) {
        sphere.indices.insert(sphere.indices.end(), triangle.begin(), triangle.end());
    }
    return sphere;
}

using Triangle = std::array<std::uint32_t, 3>;

std::vector<Triangle> sortedTriangles(const std::vector<std::uint32_t>& indices,
                                      std::size_t first = 0,
                                      std::size_t count = ~std::size_t(0)) {
    std::vector<Triangle> result;
    for (std::size_t t = first; t < std::min(first + count, indices.size() / 3); ++t) {
        result.push_back({indices[t * 3], indices[t * 3 + 1], indices[t * 3 + 2]});
    }
    std::sort(result.begin(), result.end());
    return result;
}

// Clusters cover [first, first + count) once, in order, at most 256 triangles each, and each
// triangle's corners lie in its cluster's sphere.
void expectClustersCover(const std::vector<Cluster>& clusters,
                         std::uint32_t first,
                         std::uint32_t count,
                         const std::vector<std::uint32_t>& indices,  // From level 0's first.
                         const std::vector<glm::vec4>& positions) {
    ASSERT_FALSE(clusters.empty());
    std::uint32_t next = first;
    for (const Cluster& cluster : clusters) {
        EXPECT_EQ(cluster.firstTriangle, next);
        EXPECT_GE(cluster.triangleCount, 1u);
        EXPECT_LE(cluster.triangleCount, Cluster::kMaxTriangles);
        EXPECT_GT(cluster.radius, 0.0f);
        for (std::uint32_t t = 0; t < cluster.triangleCount; ++t) {
            for (std::uint32_t corner = 0; corner < 3; ++corner) {
                const std::size_t index = std::size_t(cluster.firstTriangle + t) * 3 + corner;
                ASSERT_LT(index, indices.size());
                const glm::vec3 p(positions.at(indices[index]));
                EXPECT_LE(glm::distance(p, cluster.center), cluster.radius * 1.0001f + 1e-5f);
            }
        }
        next += cluster.triangleCount;
    }
    EXPECT_EQ(next, first + count);
}

std::vector<glm::vec4> homogeneous(const std::vector<glm::vec3>& positions) {
    std::vector<glm::vec4> result;
    for (const glm::vec3& p : positions) {
        result.push_back({p, 1.0f});
    }
    return result;
}

TEST(MeshOptimizerClustersTest, ReorderingKeepsEveryTriangleWithItsCorners) {
    const Sphere sphere = uvSphere(48, 64);
    const std::vector<glm::vec4> positions = homogeneous(sphere.positions);
    std::vector<std::uint32_t> indices = sphere.indices;
    const std::vector<Cluster> clusters = orderIntoClusters(indices, positions);
    ASSERT_EQ(indices.size(), sphere.indices.size());
    EXPECT_TRUE(sortedTriangles(indices) == sortedTriangles(sphere.indices));
    const auto triangles = std::uint32_t(indices.size() / 3);
    expectClustersCover(clusters, 0, triangles, indices, positions);
    // About 200 triangles each on a closed surface (128 vertices), not a few large ones.
    EXPECT_GE(clusters.size(), triangles / 256);
    EXPECT_LE(clusters.size(), triangles / 64);
    // Nothing to cluster: nothing changes.
    std::vector<std::uint32_t> none;
    EXPECT_TRUE(orderIntoClusters(none, positions).empty());
    std::vector<std::uint32_t> unchanged = sphere.indices;
    EXPECT_TRUE(orderIntoClusters(unchanged, {}).empty());
    EXPECT_EQ(unchanged, sphere.indices);
}

// Positions whose products overflow a float (a fuzzed file's) get no clusters rather than
// meshoptimizer's assertion on the NaN bounds: the order stays, the load goes on.
TEST(MeshOptimizerClustersTest, HugeCoordinatesGetNoClusters) {
    const Sphere sphere = uvSphere(8, 12);
    std::vector<glm::vec4> positions = homogeneous(sphere.positions);
    positions[3].y = 3e37f;
    for (const bool scan : {false, true}) {
        std::vector<std::uint32_t> indices = sphere.indices;
        EXPECT_TRUE(orderIntoClusters(indices, positions, scan).empty());
        EXPECT_EQ(indices, sphere.indices);
    }
    positions[3].y = 1e8f;  // Large, within the bound: clustered.
    std::vector<std::uint32_t> indices = sphere.indices;
    EXPECT_FALSE(orderIntoClusters(indices, positions).empty());
}

// Scanned clusters (fast loads) are runs of the triangles in their order: the same triangles in
// the same order, covered exactly once, each cluster within its bounds.
TEST(MeshOptimizerClustersTest, ScannedClustersKeepTheOrderAndCoverEveryTriangle) {
    const Sphere sphere = uvSphere(48, 64);
    const std::vector<glm::vec4> positions = homogeneous(sphere.positions);
    std::vector<std::uint32_t> indices = sphere.indices;
    const std::vector<Cluster> clusters = orderIntoClusters(indices, positions, true);
    EXPECT_EQ(indices, sphere.indices);
    const auto triangles = std::uint32_t(indices.size() / 3);
    expectClustersCover(clusters, 0, triangles, indices, positions);
    // The sphere's rows in their own order reach 128 vertices sooner than a vertex-cache order.
    EXPECT_GE(clusters.size(), triangles / 256);
    EXPECT_LE(clusters.size(), triangles / 32);
}

// A cluster is culled by its cone only when each of its triangles faces away from the eye:
// tested from points around the sphere, against every triangle's own facing.
TEST(MeshOptimizerClustersTest, ConesCullOnlyClustersFacingAway) {
    const Sphere sphere = uvSphere(32, 48);
    const std::vector<glm::vec4> positions = homogeneous(sphere.positions);
    std::vector<std::uint32_t> indices = sphere.indices;
    const std::vector<Cluster> clusters = orderIntoClusters(indices, positions);
    std::size_t culled = 0;
    for (const glm::vec3 eye : {glm::vec3(0.0f, 0.0f, 3.0f), glm::vec3(2.0f, 1.5f, -1.0f),
                                glm::vec3(-1.2f, -0.3f, 0.4f)}) {
        for (const Cluster& cluster : clusters) {
            const glm::vec3 toApex = cluster.coneApex - eye;
            if (cluster.coneCutoff >= 1.0f ||
                glm::dot(glm::normalize(toApex), cluster.coneAxis) < cluster.coneCutoff) {
                continue;
            }
            ++culled;
            for (std::uint32_t t = 0; t < cluster.triangleCount; ++t) {
                const std::size_t i = std::size_t(cluster.firstTriangle + t) * 3;
                const glm::vec3 a(positions[indices[i]]);
                const glm::vec3 b(positions[indices[i + 1]]);
                const glm::vec3 c(positions[indices[i + 2]]);
                const glm::vec3 normal = glm::cross(b - a, c - a);
                EXPECT_GE(glm::dot(normal, a - eye), 0.0f) << "a front face culled";
            }
        }
    }
    EXPECT_GT(culled, 0u);
}

test::GltfBuilder sphereModel(const std::string& alphaMode) {
    const Sphere sphere = uvSphere(40, 56);
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions(sphere.positions);
    // Without normals the loader would make flat ones, one vertex per corner: nothing to simplify.
    primitive.attributes["NORMAL"] = builder.addNormals(sphere.positions);
    primitive.indices = builder.addIndices(sphere.indices);
    primitive.material = builder.addMaterial({.alphaMode = alphaMode});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    return builder;
}

// Every level's clusters, counted from level 0's first index, cover it (levels start at whole
// triangles), and level 0 holds the file's triangles.
TEST(MeshOptimizerClustersTest, EveryLevelIsCoveredByItsClusters) {
    const test::GltfBuilder builder = sphereModel("OPAQUE");
    auto scene = loadGlb(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = scene->meshes[0].primitives[0];
    ASSERT_GE(primitive.levels.size(), 2u);
    const std::vector<glm::vec4> positions =
        scene->readFloats(*primitive.attribute(Semantic::Position));
    const Accessor& level0 = scene->accessors[primitive.indices->index()];
    const std::uint32_t triangleBytes = level0.elementSize() * 3;
    // Level 0 and every level read from the view at level 0's start, as renderers bind it.
    const BufferView& view = scene->bufferViews[level0.view.index()];
    std::vector<std::uint32_t> all;
    for (std::uint64_t offset = 0; offset + level0.elementSize() <= view.byteLength;
         offset += level0.elementSize()) {
        std::uint32_t value = 0;
        std::memcpy(&value,
                    scene->buffers[view.buffer.index()].bytes.data() + view.byteOffset + offset,
                    level0.elementSize());
        all.push_back(value);
    }
    expectClustersCover(primitive.clusters, 0, level0.count / 3, all, positions);
    for (const LevelOfDetail& level : primitive.levels) {
        const Accessor& accessor = scene->accessors[level.indices.index()];
        ASSERT_EQ(accessor.byteOffset % triangleBytes, 0u) << "not at a whole triangle";
        const auto first = std::uint32_t(accessor.byteOffset / triangleBytes);
        expectClustersCover(level.clusters, first, accessor.count / 3, all, positions);
    }
    // Level 0 holds the file's triangles (by position: the vertices were renumbered).
    auto before = loadGlb(builder, {.optimizeMeshes = false, .buildLevelsOfDetail = false});
    ASSERT_TRUE(before.ok());
    const Primitive& original = before->meshes[0].primitives[0];
    EXPECT_TRUE(original.clusters.empty());
    const std::vector<glm::vec4> originalPositions =
        before->readFloats(*original.attribute(Semantic::Position));
    auto byPosition = [](const std::vector<std::uint32_t>& indices,
                         const std::vector<glm::vec4>& values) {
        std::vector<std::array<float, 9>> triangles;
        for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
            std::array<float, 9> corners{};
            for (int c = 0; c < 3; ++c) {
                for (int k = 0; k < 3; ++k) {
                    corners[c * 3 + k] = values[indices[i + c]][k];
                }
            }
            triangles.push_back(corners);
        }
        std::sort(triangles.begin(), triangles.end());
        return triangles;
    };
    EXPECT_TRUE(byPosition(scene->readIndices(*primitive.indices), positions) ==
                byPosition(before->readIndices(*original.indices), originalPositions));
}

TEST(MeshOptimizerClustersTest, NoneForBlendingPrimitivesOrWhenTurnedOff) {
    auto scene = loadGlb(sphereModel("BLEND"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->meshes[0].primitives[0].clusters.empty());
    auto opaque = loadGlb(sphereModel("OPAQUE"), {.optimizeMeshes = false});
    ASSERT_TRUE(opaque.ok());
    EXPECT_TRUE(opaque->meshes[0].primitives[0].clusters.empty());
    for (const LevelOfDetail& level : opaque->meshes[0].primitives[0].levels) {
        EXPECT_TRUE(level.clusters.empty());
    }
    LoadOptions noClusters;
    noClusters.buildClusters = false;
    opaque = loadGlb(sphereModel("OPAQUE"), noClusters);
    ASSERT_TRUE(opaque.ok());
    EXPECT_TRUE(opaque->meshes[0].primitives[0].clusters.empty());
    EXPECT_FALSE(opaque->meshes[0].primitives[0].levels.empty());
    for (const LevelOfDetail& level : opaque->meshes[0].primitives[0].levels) {
        EXPECT_TRUE(level.clusters.empty());
    }
}

TEST(MeshOptimizerClustersTest, OnlyScenesFromTheTriangleLineGetThem) {
    auto scene = loadGlb(sphereModel("OPAQUE"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::uint64_t triangles = scene->drawnTriangleCount();
    ASSERT_GT(triangles, 0u);
    EXPECT_EQ(triangles, triangleCount(*scene, scene->meshes[0].primitives[0]));
    ASSERT_FALSE(scene->meshes[0].primitives[0].clusters.empty());
    for (const std::uint64_t line : {triangles - 1, triangles, triangles + 1}) {
        LoadOptions options;
        options.clustersFromTriangles = line;
        auto loaded = loadGlb(sphereModel("OPAQUE"), options);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message;
        EXPECT_EQ(loaded->meshes[0].primitives[0].clusters.empty(), line > triangles) << line;
        // The same triangles either way.
        EXPECT_EQ(loaded->drawnTriangleCount(), triangles);
    }
}

// A scene of only opaque, static triangles gets them below the line when the loader is asked
// (LoadOptions::clustersForOpaqueStatic: encore batch draws those with visibility at 4x); one
// that blends or masks does not.
TEST(MeshOptimizerClustersTest, OpaqueStaticScenesGetThemBelowTheLineWhenAsked) {
    for (const std::string mode : {"OPAQUE", "BLEND", "MASK"}) {
        SCOPED_TRACE(mode);
        auto plain = loadGlb(sphereModel(mode));
        ASSERT_TRUE(plain.ok()) << plain.error().message;
        const bool opaque = mode == "OPAQUE";
        EXPECT_EQ(plain->drawsOnlyOpaqueStaticTriangles(), opaque);
        LoadOptions options;
        options.clustersFromTriangles = plain->drawnTriangleCount() + 1;
        auto belowTheLine = loadGlb(sphereModel(mode), options);
        ASSERT_TRUE(belowTheLine.ok());
        EXPECT_TRUE(belowTheLine->meshes[0].primitives[0].clusters.empty());
        options.clustersForOpaqueStatic = true;
        auto asked = loadGlb(sphereModel(mode), options);
        ASSERT_TRUE(asked.ok());
        EXPECT_EQ(asked->meshes[0].primitives[0].clusters.empty(), !opaque);
    }
}

}  // namespace
}  // namespace encore::scene
