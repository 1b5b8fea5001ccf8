// What load-time mesh optimisation (MeshOptimizer.h) makes of each kind of vertex stream, on
// SceneData built by hand with the answers worked out by hand: the order the vertices are
// renumbered in, the new streams' strides and counts, the streams that must keep their order,
// and the buffers released once no primitive reads them. Each stream lies in a buffer of its
// own, so the released buffers show which streams the optimiser saw each primitive read.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "scene/MeshOptimizer.h"

namespace encore::scene {
namespace {

// A SceneData made by hand, without the loader: each accessor in a buffer of its own, so that
// which buffers optimizeMeshes releases shows which accessors it saw the primitives read.
struct HandBuiltScene {
    SceneData scene;

    // `count` elements, tightly packed; element v's byte i is `seed + 8 * v + i`, so that every
    // element of every stream is told apart by its bytes.
    AccessorId addStream(ComponentType type,
                         std::uint8_t componentCount,
                         bool normalized,
                         std::uint32_t count,
                         std::uint8_t seed) {
        const std::uint32_t size = componentSize(type) * componentCount;
        std::vector<std::uint8_t> bytes(std::size_t(size) * count);
        for (std::uint32_t v = 0; v < count; ++v) {
            for (std::uint32_t i = 0; i < size; ++i) {
                bytes[v * size + i] = std::uint8_t(seed + 8 * v + i);
            }
        }
        return addAccessor(std::move(bytes), type, componentCount, normalized, count);
    }

    AccessorId addPositions(const std::vector<glm::vec3>& positions) {
        std::vector<std::uint8_t> bytes(positions.size() * 12);
        std::memcpy(bytes.data(), positions.data(), bytes.size());
        return addAccessor(std::move(bytes), ComponentType::Float32, 3, false,
                           std::uint32_t(positions.size()));
    }

    AccessorId addIndices(const std::vector<std::uint16_t>& indices) {
        std::vector<std::uint8_t> bytes(indices.size() * 2);
        std::memcpy(bytes.data(), indices.data(), bytes.size());
        return addAccessor(std::move(bytes), ComponentType::Uint16, 1, false,
                           std::uint32_t(indices.size()));
    }

    MaterialId addMaterial(AlphaMode alphaMode) {
        Material material;
        material.alphaMode = alphaMode;
        scene.materials.push_back(material);
        return MaterialId(scene.materials.size() - 1);
    }

    // The element bytes of `accessor` (tightly packed) in the order `order` gives (old indices).
    std::vector<std::uint8_t> elementsInOrder(AccessorId accessor,
                                              const std::vector<std::uint32_t>& order) const {
        const std::vector<std::uint8_t> packed = scene.packedAccessorBytes(accessor);
        const std::size_t size = scene.accessors[accessor.index()].elementSize();
        std::vector<std::uint8_t> result;
        for (std::uint32_t v : order) {
            result.insert(result.end(), packed.begin() + v * size, packed.begin() + (v + 1) * size);
        }
        return result;
    }

  private:
    AccessorId addAccessor(std::vector<std::uint8_t> bytes,
                           ComponentType type,
                           std::uint8_t componentCount,
                           bool normalized,
                           std::uint32_t count) {
        BufferView view;
        view.buffer = BufferId(scene.buffers.size());
        view.byteLength = bytes.size();
        scene.buffers.push_back(
            Buffer{"hand-built " + std::to_string(scene.buffers.size()), std::move(bytes)});
        scene.bufferViews.push_back(view);
        Accessor accessor;
        accessor.view = BufferViewId(scene.bufferViews.size() - 1);
        accessor.count = count;
        accessor.componentType = type;
        accessor.componentCount = componentCount;
        accessor.normalized = normalized;
        accessor.byteStride = accessor.elementSize();
        scene.accessors.push_back(accessor);
        return AccessorId(scene.accessors.size() - 1);
    }
};

MeshOptimizerOptions orderOnly() {
    MeshOptimizerOptions options;
    options.buildLevelsOfDetail = false;
    return options;
}

// A quad of two triangles over vertices 0..3 and a fifth vertex no triangle uses.
const std::vector<glm::vec3> kQuadPositions = {{0, 0, 0},
                                               {1, 0, 0},
                                               {1, 1, 0},
                                               {0, 1, 0},
                                               {2, 2, 0}};
const std::vector<std::uint16_t> kQuadIndices = {3, 1, 0, 3, 2, 1};

// The index triples of a triangle list, sorted: the triangles whatever their order.
std::vector<std::array<std::uint32_t, 3>> sortedTriangles(
    const std::vector<std::uint32_t>& indices) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

TEST(MeshOptimizerStreamsTest, RenumbersEveryVertexStreamInFirstUseOrder) {
    // Every kind of per-vertex data a primitive holds, each in a buffer of its own: attributes
    // of 12, 3, 4 and 8 bytes (TEXCOORD_0 and TEXCOORD_1 reading one accessor), and morph
    // target deltas of each kind in two targets. Blended, so the triangle order stays and the
    // renumbering is known: vertices in the order the indices first use them (3, 1, 0, 2),
    // then the unused one (4).
    HandBuiltScene built;
    const AccessorId position = built.addPositions(kQuadPositions);
    const AccessorId normal = built.addStream(ComponentType::Int8, 3, true, 5, 10);
    const AccessorId texcoord = built.addStream(ComponentType::Uint16, 2, true, 5, 50);
    const AccessorId color = built.addStream(ComponentType::Uint8, 3, true, 5, 90);
    const AccessorId joints = built.addStream(ComponentType::Uint16, 4, false, 5, 130);
    const AccessorId positionDelta0 = built.addStream(ComponentType::Float32, 3, false, 5, 1);
    const AccessorId normalDelta0 = built.addStream(ComponentType::Float32, 3, false, 5, 2);
    const AccessorId tangentDelta0 = built.addStream(ComponentType::Float32, 3, false, 5, 3);
    const AccessorId positionDelta1 = built.addStream(ComponentType::Float32, 3, false, 5, 4);
    const AccessorId indices = built.addIndices(kQuadIndices);
    ASSERT_EQ(built.scene.buffers.size(), 10u);

    Primitive primitive;
    primitive.attributes = {{Semantic::Position, position},  {Semantic::Normal, normal},
                            {Semantic::Texcoord0, texcoord}, {Semantic::Texcoord1, texcoord},
                            {Semantic::Color0, color},       {Semantic::Joints0, joints}};
    primitive.targets = {{positionDelta0, normalDelta0, tangentDelta0}, {positionDelta1, {}, {}}};
    primitive.indices = indices;
    primitive.material = built.addMaterial(AlphaMode::Blend);
    primitive.vertexCount = 5;
    built.scene.meshes.push_back(Mesh{"quad", {primitive}, {0.0f, 0.0f}});
    const HandBuiltScene before = built;

    const auto report = optimizeMeshes(built.scene, orderOnly());
    ASSERT_TRUE(report.ok()) << report.error().message;
    const SceneData& after = built.scene;
    const Primitive& optimised = after.meshes[0].primitives[0];

    EXPECT_EQ(after.readIndices(*optimised.indices),
              (std::vector<std::uint32_t>{0, 1, 2, 0, 3, 1}));
    EXPECT_EQ(optimised.vertexCount, 5u);
    // Blended: counted as reordered in part (its triangles kept their order).
    EXPECT_EQ(report->primitivesReordered, 0u);
    EXPECT_EQ(report->primitivesIndicesOnly, 1u);
    EXPECT_EQ(report->levelsBuilt, 0u);
    // Nine streams (TEXCOORD_0 and TEXCOORD_1 share one) and the indices moved to new data, in
    // one new buffer; no primitive reads any of the ten old buffers, so all are emptied.
    EXPECT_EQ(after.accessors.size(), before.scene.accessors.size() + 10);
    ASSERT_EQ(after.buffers.size(), 11u);
    EXPECT_EQ(report->buffersReleased, 10u);
    for (std::size_t b = 0; b < 10; ++b) {
        EXPECT_TRUE(after.buffers[b].bytes.empty()) << "buffer " << b;
    }
    EXPECT_EQ(optimised.attributes[2].accessor, optimised.attributes[3].accessor)
        << "TEXCOORD_0 and TEXCOORD_1 still read one accessor";

    const std::vector<std::uint32_t> oldOfNew = {3, 1, 0, 2, 4};
    struct Expected {
        const char* name;
        AccessorId old;
        AccessorId now;
        std::uint32_t stride;  // The element size rounded up to 4 bytes.
    };
    const Expected streams[] = {
        {"POSITION", position, optimised.attributes[0].accessor, 12},
        {"NORMAL", normal, optimised.attributes[1].accessor, 4},
        {"TEXCOORD_0", texcoord, optimised.attributes[2].accessor, 4},
        {"COLOR_0", color, optimised.attributes[4].accessor, 4},
        {"JOINTS_0", joints, optimised.attributes[5].accessor, 8},
        {"target 0 POSITION", positionDelta0, *optimised.targets[0].position, 12},
        {"target 0 NORMAL", normalDelta0, *optimised.targets[0].normal, 12},
        {"target 0 TANGENT", tangentDelta0, *optimised.targets[0].tangent, 12},
        {"target 1 POSITION", positionDelta1, *optimised.targets[1].position, 12},
    };
    ASSERT_TRUE(optimised.targets.size() == 2 && !optimised.targets[1].normal &&
                !optimised.targets[1].tangent);
    for (const Expected& stream : streams) {
        SCOPED_TRACE(stream.name);
        EXPECT_NE(stream.now, stream.old);
        const Accessor& was = before.scene.accessors[stream.old.index()];
        const Accessor& is = after.accessors[stream.now.index()];
        EXPECT_EQ(is.count, 5u);
        EXPECT_EQ(is.componentType, was.componentType);
        EXPECT_EQ(is.componentCount, was.componentCount);
        EXPECT_EQ(is.normalized, was.normalized);
        EXPECT_EQ(is.byteStride, stream.stride);
        EXPECT_EQ(after.bufferViews[is.view.index()].byteStride, stream.stride);
        EXPECT_EQ(after.bufferViews[is.view.index()].buffer, BufferId(std::size_t(10)));
        EXPECT_EQ(after.packedAccessorBytes(stream.now),
                  before.elementsInOrder(stream.old, oldOfNew));
    }
}

TEST(MeshOptimizerStreamsTest, AStreamSharedThroughAMorphTargetKeepsTheVertexOrder) {
    // Two primitives with vertices of their own but one morph target delta between them:
    // renumbering either would scramble the other's deltas.
    HandBuiltScene built;
    const AccessorId sharedDelta = built.addStream(ComponentType::Float32, 3, false, 5, 1);
    Mesh mesh{"two parts", {}, {0.0f}};
    for (std::uint8_t p = 0; p < 2; ++p) {
        Primitive primitive;
        primitive.attributes = {
            {Semantic::Position, built.addPositions(kQuadPositions)},
            {Semantic::Normal, built.addStream(ComponentType::Float32, 3, false, 5, 20 + p)}};
        primitive.targets = {{sharedDelta, {}, {}}};
        primitive.indices = built.addIndices(kQuadIndices);
        primitive.material = built.addMaterial(AlphaMode::Opaque);
        primitive.vertexCount = 5;
        mesh.primitives.push_back(primitive);
    }
    built.scene.meshes.push_back(mesh);
    const SceneData before = built.scene;

    const auto report = optimizeMeshes(built.scene, orderOnly());
    ASSERT_TRUE(report.ok()) << report.error().message;
    EXPECT_EQ(report->primitivesReordered, 0u);
    EXPECT_EQ(report->primitivesIndicesOnly, 2u);
    for (std::size_t p = 0; p < 2; ++p) {
        SCOPED_TRACE("primitive " + std::to_string(p));
        const Primitive& was = before.meshes[0].primitives[p];
        const Primitive& is = built.scene.meshes[0].primitives[p];
        EXPECT_EQ(is.attributes[0].accessor, was.attributes[0].accessor);
        EXPECT_EQ(is.attributes[1].accessor, was.attributes[1].accessor);
        EXPECT_EQ(is.targets[0].position, sharedDelta);
        EXPECT_NE(is.indices, was.indices);
    }
    // The same triangles, corners in order, over the same vertex numbers.
    for (std::size_t p = 0; p < 2; ++p) {
        EXPECT_EQ(
            sortedTriangles(built.scene.readIndices(*built.scene.meshes[0].primitives[p].indices)),
            sortedTriangles(std::vector<std::uint32_t>(kQuadIndices.begin(), kQuadIndices.end())));
    }
    // Only the two index buffers are read no more; the delta's and the attributes' still are.
    EXPECT_EQ(report->buffersReleased, 2u);
    EXPECT_FALSE(built.scene.buffers[0].bytes.empty());
}

TEST(MeshOptimizerStreamsTest, AMorphDeltaOfTheWrongLengthKeepsTheVertexOrder) {
    // Only a hand-built SceneData gets here (the loader refuses it): a TANGENT delta with one
    // element fewer than the primitive has vertices cannot be renumbered with the others.
    HandBuiltScene built;
    Primitive primitive;
    primitive.attributes = {
        {Semantic::Position, built.addPositions(kQuadPositions)},
        {Semantic::Normal, built.addStream(ComponentType::Float32, 3, false, 5, 20)}};
    primitive.targets = {{{}, {}, built.addStream(ComponentType::Float32, 3, false, 4, 1)}};
    primitive.indices = built.addIndices(kQuadIndices);
    primitive.material = built.addMaterial(AlphaMode::Opaque);
    primitive.vertexCount = 5;
    built.scene.meshes.push_back(Mesh{"quad", {primitive}, {0.0f}});
    const SceneData before = built.scene;

    const auto report = optimizeMeshes(built.scene, orderOnly());
    ASSERT_TRUE(report.ok()) << report.error().message;
    EXPECT_EQ(report->primitivesReordered, 0u);
    EXPECT_EQ(report->primitivesIndicesOnly, 1u);
    const Primitive& is = built.scene.meshes[0].primitives[0];
    EXPECT_EQ(is.attributes[0].accessor, primitive.attributes[0].accessor);
    EXPECT_EQ(is.attributes[1].accessor, primitive.attributes[1].accessor);
    EXPECT_EQ(is.targets[0].tangent, primitive.targets[0].tangent);
    EXPECT_EQ(built.scene.accessors.size(), before.accessors.size() + 1);  // The indices only.
}

}  // namespace
}  // namespace encore::scene
