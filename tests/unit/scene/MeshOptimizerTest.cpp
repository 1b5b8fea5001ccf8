// Load-time mesh optimisation (MeshOptimizer.h): the same triangles over the same vertex values
// before and after, the index layout of Primitive::levels that renderers rely on, the halving
// and error order of the chain, and the cases that must keep their order. What becomes of each
// kind of vertex stream, worked out by hand, is in MeshOptimizerStreamsTest.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "scene/MeshOptimizer.h"

namespace encore::scene {
namespace {

using testing::loadGlb;

// One vertex as the test sees it: the bytes of each of its values, named by what the value is
// (an attribute's semantic, or a morph target's delta), so that two loads compare whatever
// accessors hold the values or in which order. Every field of Primitive that holds per-vertex
// data is read here by name, on purpose not through a list of streams like the optimiser's.
using Vertex = std::map<std::string, std::vector<std::uint8_t>>;
using Triangle = std::array<Vertex, 3>;

std::vector<Vertex> vertices(const SceneData& scene, const Primitive& primitive) {
    std::vector<Vertex> result(primitive.vertexCount);
    auto read = [&](const std::string& name, AccessorId accessor) {
        const std::vector<std::uint8_t> packed = scene.packedAccessorBytes(accessor);
        const std::size_t size = scene.accessors[accessor.index()].elementSize();
        EXPECT_EQ(packed.size(), size * primitive.vertexCount) << name;
        for (std::size_t v = 0; v < primitive.vertexCount && (v + 1) * size <= packed.size(); ++v) {
            result[v][name].assign(packed.begin() + v * size, packed.begin() + (v + 1) * size);
        }
    };
    for (const VertexAttribute& attribute : primitive.attributes) {
        read(std::string(semanticName(attribute.semantic)), attribute.accessor);
    }
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
        const std::string target = "target " + std::to_string(t) + " ";
        if (primitive.targets[t].position) {
            read(target + "POSITION", *primitive.targets[t].position);
        }
        if (primitive.targets[t].normal) {
            read(target + "NORMAL", *primitive.targets[t].normal);
        }
        if (primitive.targets[t].tangent) {
            read(target + "TANGENT", *primitive.targets[t].tangent);
        }
    }
    return result;
}

// The primitive's triangles as vertex values, in draw order, each with its corners in order.
std::vector<Triangle> triangles(const SceneData& scene, const Primitive& primitive) {
    const std::vector<Vertex> values = vertices(scene, primitive);
    std::vector<std::uint32_t> indices(primitive.vertexCount);
    if (primitive.indices) {
        indices = scene.readIndices(*primitive.indices);
    } else {
        std::iota(indices.begin(), indices.end(), 0u);
    }
    std::vector<Triangle> result;
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        result.push_back(
            {values.at(indices[i]), values.at(indices[i + 1]), values.at(indices[i + 2])});
    }
    return result;
}

template <typename T>
std::vector<T> sorted(std::vector<T> values) {
    std::sort(values.begin(), values.end());
    return values;
}

// Every primitive draws the same triangles (as vertex values, corners in order) in both scenes;
// with `sameOrder` also in the same order. Its vertices are the same ones, renumbered at most:
// as many, with the same values.
void expectSameTriangles(const SceneData& before, const SceneData& after, bool sameOrder = false) {
    ASSERT_EQ(before.meshes.size(), after.meshes.size());
    for (std::size_t m = 0; m < before.meshes.size(); ++m) {
        ASSERT_EQ(before.meshes[m].primitives.size(), after.meshes[m].primitives.size());
        for (std::size_t p = 0; p < before.meshes[m].primitives.size(); ++p) {
            SCOPED_TRACE("mesh " + std::to_string(m) + ", primitive " + std::to_string(p));
            const Primitive& a = before.meshes[m].primitives[p];
            const Primitive& b = after.meshes[m].primitives[p];
            EXPECT_EQ(a.vertexCount, b.vertexCount);
            EXPECT_EQ(a.topology, b.topology);
            ASSERT_EQ(a.attributes.size(), b.attributes.size());
            ASSERT_EQ(a.targets.size(), b.targets.size());
            for (std::size_t i = 0; i < a.attributes.size(); ++i) {
                EXPECT_EQ(a.attributes[i].semantic, b.attributes[i].semantic);
                const Accessor& x = before.accessors[a.attributes[i].accessor.index()];
                const Accessor& y = after.accessors[b.attributes[i].accessor.index()];
                EXPECT_EQ(x.componentType, y.componentType);
                EXPECT_EQ(x.componentCount, y.componentCount);
                EXPECT_EQ(x.normalized, y.normalized);
                EXPECT_EQ(x.min, y.min);
                EXPECT_EQ(x.max, y.max);
            }
            EXPECT_TRUE(sorted(vertices(before, a)) == sorted(vertices(after, b)));
            if (sameOrder) {
                EXPECT_TRUE(triangles(before, a) == triangles(after, b));
            } else {
                EXPECT_TRUE(sorted(triangles(before, a)) == sorted(triangles(after, b)));
            }
        }
    }
}

// What renderers rely on (SceneData.h): one view, level 0 at its start, levels after it at
// 4-byte-aligned offsets with the same index type, each at most half the triangles of the one
// before, errors non-decreasing, every index below the vertex count.
void expectLevelLayout(const SceneData& scene, const Primitive& primitive) {
    if (primitive.levels.empty()) {
        return;
    }
    ASSERT_TRUE(primitive.indices);
    const Accessor& level0 = scene.accessors[primitive.indices->index()];
    const BufferView& view = scene.bufferViews[level0.view.index()];
    EXPECT_EQ(level0.byteOffset, 0u);
    EXPECT_EQ(view.byteOffset % 4, 0u);
    const std::uint32_t size = level0.elementSize();
    EXPECT_EQ(size, primitive.vertexCount <= 0xFFFF ? 2u : 4u);
    std::uint64_t end = level0.byteOffset + std::uint64_t(level0.count) * size;
    std::uint32_t previousTriangles = level0.count / 3;
    float previousError = 0.0f;
    for (const LevelOfDetail& level : primitive.levels) {
        const Accessor& accessor = scene.accessors[level.indices.index()];
        EXPECT_EQ(accessor.view, level0.view);
        EXPECT_EQ(accessor.componentType, level0.componentType);
        EXPECT_EQ(accessor.byteStride, size);
        EXPECT_EQ(accessor.byteOffset % 4, 0u);
        EXPECT_GE(accessor.byteOffset, end);  // Levels do not overlap, in order.
        end = accessor.byteOffset + std::uint64_t(accessor.count) * size;
        EXPECT_LE(end, view.byteLength);
        // The draw a renderer makes: firstIndex into the view bound from level 0's offset.
        EXPECT_EQ((accessor.byteOffset - level0.byteOffset) % size, 0u);

        EXPECT_EQ(accessor.count % 3, 0u);
        EXPECT_GT(accessor.count, 0u);
        EXPECT_LE(accessor.count / 3, previousTriangles / 2);
        previousTriangles = accessor.count / 3;
        EXPECT_GE(level.error, previousError);
        EXPECT_TRUE(std::isfinite(level.error));
        previousError = level.error;
        const std::vector<std::uint32_t> indices = scene.readIndices(level.indices);
        ASSERT_EQ(indices.size(), accessor.count);
        EXPECT_LT(*std::max_element(indices.begin(), indices.end()), primitive.vertexCount);
    }
}

struct SphereOptions {
    std::uint32_t rings = 24;
    std::uint32_t segments = 32;
    std::string alphaMode = "OPAQUE";
    bool shuffled = true;  // Triangles and vertices in random order, as no exporter leaves them.
};

// A UV sphere with every kind of vertex stream: normals, texture coordinates, colours,
// joints and weights, and two morph targets (a POSITION delta; NORMAL and TANGENT deltas).
test::GltfBuilder sphereBuilder(const SphereOptions& options = {}) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> texcoords;
    for (std::uint32_t r = 0; r <= options.rings; ++r) {
        for (std::uint32_t s = 0; s <= options.segments; ++s) {
            const float theta = 3.14159265f * float(r) / float(options.rings);
            const float phi = 6.2831853f * float(s) / float(options.segments);
            positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                 std::sin(theta) * std::sin(phi)});
            texcoords.push_back(
                {float(s) / float(options.segments), float(r) / float(options.rings)});
        }
    }
    std::vector<std::uint32_t> indices;
    const std::uint32_t row = options.segments + 1;
    for (std::uint32_t r = 0; r < options.rings; ++r) {
        for (std::uint32_t s = 0; s < options.segments; ++s) {
            const std::uint32_t a = r * row + s, b = a + row;
            indices.insert(indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
    std::vector<std::uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    if (options.shuffled) {
        std::mt19937 random(7);
        std::shuffle(order.begin(), order.end(), random);  // order[new] = old
        std::vector<std::uint32_t> inverse(order.size());
        for (std::uint32_t v = 0; v < order.size(); ++v) {
            inverse[order[v]] = v;
        }
        for (std::uint32_t& index : indices) {
            index = inverse[index];
        }
        std::vector<std::array<std::uint32_t, 3>> corners(indices.size() / 3);
        std::memcpy(corners.data(), indices.data(), indices.size() * 4);
        std::shuffle(corners.begin(), corners.end(), random);
        std::memcpy(indices.data(), corners.data(), indices.size() * 4);
    }
    std::vector<glm::vec3> shuffledPositions, normals, deltas, normalDeltas, tangentDeltas;
    std::vector<glm::vec2> shuffledTexcoords;
    std::vector<glm::vec4> colors;
    std::vector<std::uint16_t> joints;
    std::vector<float> weights;
    for (std::uint32_t v = 0; v < order.size(); ++v) {
        const glm::vec3 p = positions[order[v]];
        shuffledPositions.push_back(p);
        normals.push_back(glm::normalize(p + glm::vec3(0.0f, 1e-6f, 0.0f)));
        shuffledTexcoords.push_back(texcoords[order[v]]);
        colors.push_back({p * 0.5f + 0.5f, 1.0f});
        joints.insert(joints.end(), {std::uint16_t(order[v] % 3), 0, 0, 0});
        weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
        deltas.push_back(p * 0.25f);
        normalDeltas.push_back(glm::vec3(p.y, p.z, p.x) * 0.125f);
        tangentDeltas.push_back(glm::vec3(p.z, 0.0f, -p.x) * 0.5f);
    }

    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions(shuffledPositions);
    primitive.attributes["NORMAL"] = builder.addNormals(normals);
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords(shuffledTexcoords);
    primitive.attributes["COLOR_0"] = builder.addColors(colors);
    primitive.attributes["JOINTS_0"] = builder.addAccessor(joints, "VEC4");
    primitive.attributes["WEIGHTS_0"] = builder.addAccessor(weights, "VEC4");
    primitive.indices = builder.addIndices(indices);
    primitive.material = builder.addMaterial({.alphaMode = options.alphaMode});
    const std::uint32_t positionTarget = builder.addPositions(deltas);
    const std::uint32_t normalTarget = builder.addNormals(normalDeltas);
    const std::uint32_t tangentTarget = builder.addNormals(tangentDeltas);
    const std::uint32_t mesh = builder.addMesh(primitive);
    builder.json()["meshes"][mesh]["primitives"][0]["targets"] = {
        {{"POSITION", positionTarget}}, {{"NORMAL", normalTarget}, {"TANGENT", tangentTarget}}};
    builder.addScene({builder.addNode({.mesh = mesh})});
    return builder;
}

LoadOptions unoptimised() {
    LoadOptions options;
    options.optimizeMeshes = false;
    options.buildLevelsOfDetail = false;
    return options;
}

TEST(MeshOptimizerTest, KeepsEveryTriangleAndVertexValue) {
    const test::GltfBuilder builder = sphereBuilder();
    auto before = loadGlb(builder, unoptimised());
    auto after = loadGlb(builder);
    ASSERT_TRUE(before.ok()) << before.error().message;
    ASSERT_TRUE(after.ok()) << after.error().message;
    const Primitive& primitive = after->meshes[0].primitives[0];
    ASSERT_EQ(primitive.attributes.size(), 6u);  // Joints and weights kept without a skin.
    ASSERT_EQ(primitive.targets.size(), 2u);
    ASSERT_TRUE(primitive.targets[0].position && primitive.targets[1].normal &&
                primitive.targets[1].tangent);
    expectSameTriangles(*before, *after);
    // Something did change: the shuffled vertices now come in the order triangles use them.
    const std::vector<std::uint32_t> indices = after->readIndices(*primitive.indices);
    std::uint32_t next = 0;
    for (std::uint32_t index : indices) {
        EXPECT_LE(index, next) << "a vertex is used before every lower-numbered one";
        next = std::max(next, index + 1);
    }
    EXPECT_NE(before->readIndices(*before->meshes[0].primitives[0].indices), indices);
    // Every stream moved, so the GLB's BIN chunk holds nothing any primitive reads: released.
    EXPECT_EQ(after->buffers[0].name, "GLB BIN chunk");
    EXPECT_TRUE(after->buffers[0].bytes.empty());
}

// Transformed vertices per triangle with a 16-entry FIFO cache, roughly what GPUs have.
double fifoMissesPerTriangle(const std::vector<std::uint32_t>& indices) {
    std::vector<std::uint32_t> cache;
    std::size_t misses = 0;
    for (std::uint32_t index : indices) {
        if (std::find(cache.begin(), cache.end(), index) == cache.end()) {
            ++misses;
            cache.push_back(index);
            if (cache.size() > 16) {
                cache.erase(cache.begin());
            }
        }
    }
    return double(misses) / double(indices.size() / 3);
}

TEST(MeshOptimizerTest, ImprovesTheVertexCacheHitRate) {
    const test::GltfBuilder builder = sphereBuilder();
    auto before = loadGlb(builder, unoptimised());
    ASSERT_TRUE(before.ok()) << before.error().message;
    const double old =
        fifoMissesPerTriangle(before->readIndices(*before->meshes[0].primitives[0].indices));
    std::vector<std::uint32_t> thoroughIndices;
    for (VertexCacheOrder order : {VertexCacheOrder::Thorough, VertexCacheOrder::Fast}) {
        SCOPED_TRACE(order == VertexCacheOrder::Fast ? "fast" : "thorough");
        LoadOptions options;
        options.vertexCacheOrder = order;
        auto after = loadGlb(builder, options);
        ASSERT_TRUE(after.ok()) << after.error().message;
        expectSameTriangles(*before, *after);
        const std::vector<std::uint32_t> indices =
            after->readIndices(*after->meshes[0].primitives[0].indices);
        const double now = fifoMissesPerTriangle(indices);
        EXPECT_LT(now, 0.8 * old) << old << " -> " << now;
        // The two optimisers really differ (the option reaches meshoptimizer), and their levels
        // of detail are ordered too.
        if (order == VertexCacheOrder::Thorough) {
            thoroughIndices = indices;
        } else {
            EXPECT_NE(indices, thoroughIndices);
        }
        const Primitive& primitive = after->meshes[0].primitives[0];
        ASSERT_FALSE(primitive.levels.empty());
        expectLevelLayout(*after, primitive);
    }
}

TEST(MeshOptimizerTest, BuildsAHalvingChainInOneIndexView) {
    auto scene = loadGlb(sphereBuilder());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = scene->meshes[0].primitives[0];
    EXPECT_GE(primitive.levels.size(), 3u);
    expectLevelLayout(*scene, primitive);
    // The budget bounds every level: a unit sphere's extent is its diameter, 2.
    EXPECT_LE(primitive.levels.back().error, MeshOptimizerOptions{}.maxRelativeError * 2.0f);
    EXPECT_GT(primitive.levels.back().error, 0.0f);
}

TEST(MeshOptimizerTest, OptionsTurnEachPartOff) {
    const test::GltfBuilder builder = sphereBuilder();
    LoadOptions noLevels;
    noLevels.buildLevelsOfDetail = false;
    auto scene = loadGlb(builder, noLevels);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->meshes[0].primitives[0].levels.empty());

    LoadOptions levelsOnly;
    levelsOnly.optimizeMeshes = false;
    auto before = loadGlb(builder, unoptimised());
    scene = loadGlb(builder, levelsOnly);
    ASSERT_TRUE(scene.ok() && before.ok());
    EXPECT_FALSE(scene->meshes[0].primitives[0].levels.empty());
    expectLevelLayout(*scene, scene->meshes[0].primitives[0]);
    expectSameTriangles(*before, *scene, /*sameOrder=*/true);
}

TEST(MeshOptimizerTest, BlendedPrimitivesKeepTheirTriangleOrder) {
    const test::GltfBuilder builder = sphereBuilder({.alphaMode = "BLEND"});
    auto before = loadGlb(builder, unoptimised());
    auto after = loadGlb(builder);
    ASSERT_TRUE(before.ok() && after.ok());
    expectSameTriangles(*before, *after, /*sameOrder=*/true);
    // The vertices are still renumbered in the order the triangles use them.
    EXPECT_NE(after->meshes[0].primitives[0].attributes[0].accessor,
              before->meshes[0].primitives[0].attributes[0].accessor);
}

TEST(MeshOptimizerTest, SharedVertexStreamsKeepTheirOrder) {
    // Two primitives (two materials) over one set of vertices: a quad strip of 4 x 8 quads,
    // its left half in one primitive and its right half in the other.
    test::GltfBuilder builder;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    for (int y = 0; y <= 4; ++y) {
        for (int x = 0; x <= 8; ++x) {
            positions.push_back({float(x), float(y), 0.1f * float((x * 7 + y * 3) % 5)});
            normals.push_back({0.0f, 0.0f, 1.0f});
        }
    }
    std::vector<std::uint16_t> left, right;
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) {
            const auto a = std::uint16_t(y * 9 + x), b = std::uint16_t(a + 9);
            auto& half = x < 4 ? left : right;
            half.insert(half.end(), {b, a, std::uint16_t(a + 1), b, std::uint16_t(a + 1),
                                     std::uint16_t(b + 1)});
        }
    }
    std::reverse(left.begin(), left.end());  // Give the cache optimiser something to do.
    const std::map<std::string, std::uint32_t> attributes = {
        {"POSITION", builder.addPositions(positions)}, {"NORMAL", builder.addNormals(normals)}};
    const std::uint32_t mesh = builder.addMesh(std::vector<test::GltfBuilder::PrimitiveDesc>{
        {.attributes = attributes,
         .indices = builder.addIndices(left),
         .material = builder.addMaterial({})},
        {.attributes = attributes,
         .indices = builder.addIndices(right),
         .material = builder.addMaterial({.baseColor = {1, 0, 0, 1}})}});
    builder.addScene({builder.addNode({.mesh = mesh})});

    auto before = loadGlb(builder, unoptimised());
    auto after = loadGlb(builder);
    ASSERT_TRUE(before.ok()) << before.error().message;
    ASSERT_TRUE(after.ok()) << after.error().message;
    expectSameTriangles(*before, *after);
    for (std::size_t p = 0; p < 2; ++p) {
        const Primitive& a = before->meshes[0].primitives[p];
        const Primitive& b = after->meshes[0].primitives[p];
        for (std::size_t i = 0; i < a.attributes.size(); ++i) {
            EXPECT_EQ(a.attributes[i].accessor, b.attributes[i].accessor) << "stream " << i;
        }
        EXPECT_NE(a.indices, b.indices);  // The triangles were still reordered.
        expectLevelLayout(*after, b);
    }
    EXPECT_EQ(after->buffers[0].bytes, before->buffers[0].bytes);  // Still read: kept.
}

TEST(MeshOptimizerTest, LeavesOtherTopologiesAlone) {
    for (std::uint32_t mode : {0u, 1u, 3u, 5u}) {
        test::GltfBuilder builder;
        const std::uint32_t positions = builder.addPositions(
            {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 0}, {3, 1, 0}});
        const std::uint32_t indices =
            builder.addIndices(std::vector<std::uint16_t>{5, 4, 3, 2, 1, 0});
        builder.addScene({builder.addNode(
            {.mesh = builder.addMesh(
                 {.attributes = {{"POSITION", positions}}, .indices = indices, .mode = mode})})});
        auto before = loadGlb(builder, unoptimised());
        auto after = loadGlb(builder);
        ASSERT_TRUE(before.ok() && after.ok()) << mode;
        const Primitive& a = before->meshes[0].primitives[0];
        const Primitive& b = after->meshes[0].primitives[0];
        EXPECT_EQ(a.indices, b.indices) << mode;
        EXPECT_TRUE(b.levels.empty()) << mode;
        EXPECT_EQ(before->buffers.size(), after->buffers.size()) << mode;
    }
    // Non-indexed triangles too.
    auto before = loadGlb(testing::triangleBuilder(), unoptimised());
    auto after = loadGlb(testing::triangleBuilder());
    ASSERT_TRUE(before.ok() && after.ok());
    EXPECT_FALSE(after->meshes[0].primitives[0].indices);
    EXPECT_EQ(before->buffers.size(), after->buffers.size());
}

TEST(MeshOptimizerTest, RefusesIndicesPastTheVertexCountAndChangesNothing) {
    auto loaded = loadGlb(sphereBuilder({.rings = 4, .segments = 4}), unoptimised());
    ASSERT_TRUE(loaded.ok());
    SceneData scene = std::move(*loaded);
    scene.meshes[0].primitives[0].vertexCount = 3;  // What a hand-built SceneData might do.
    const std::size_t buffers = scene.buffers.size();
    const std::size_t accessors = scene.accessors.size();
    const auto result = optimizeMeshes(scene);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(result.error().message.find("mesh 0, primitive 0"), std::string::npos)
        << result.error().message;
    EXPECT_NE(result.error().message.find("vertex count (3)"), std::string::npos)
        << result.error().message;
    EXPECT_EQ(scene.buffers.size(), buffers);
    EXPECT_EQ(scene.accessors.size(), accessors);
    EXPECT_TRUE(scene.meshes[0].primitives[0].levels.empty());
}

// Real models, when ../shared/models is there: textured, skinned, morphed and multi-primitive
// ones keep every triangle, and every chain has the documented layout.
TEST(MeshOptimizerTest, SharedModelsKeepTheirTriangles) {
    const auto models = test::sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "../shared/models is absent beside the clone";
    }
    const char* files[] = {"BoxTextured/glTF/BoxTextured.gltf",
                           "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb",
                           "Fox/glTF-Binary/Fox.glb",
                           "BrainStem/glTF-Binary/BrainStem.glb",
                           "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
                           "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb",
                           "Duck/glTF-Quantized/Duck.gltf"};
    std::size_t levels = 0;
    for (const char* file : files) {
        const std::filesystem::path path = *models / file;
        if (!std::filesystem::exists(path)) {
            continue;
        }
        SCOPED_TRACE(file);
        LoadOptions plain = unoptimised();
        plain.decodeImages = false;
        LoadOptions optimised;
        optimised.decodeImages = false;
        auto before = loadScene(path, plain);
        auto after = loadScene(path, optimised);
        ASSERT_TRUE(before.ok()) << before.error().message;
        ASSERT_TRUE(after.ok()) << after.error().message;
        expectSameTriangles(*before, *after);
        for (const Mesh& mesh : after->meshes) {
            for (const Primitive& primitive : mesh.primitives) {
                expectLevelLayout(*after, primitive);
                levels += primitive.levels.size();
            }
        }
    }
    EXPECT_GT(levels, 0u);
}

}  // namespace
}  // namespace encore::scene
