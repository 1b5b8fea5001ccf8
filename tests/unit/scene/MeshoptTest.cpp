// EXT_meshopt_compression: compressed views are decoded and the fallback buffer is never read.

#include <gtest/gtest.h>

#include <meshoptimizer.h>

#include "SceneTestUtils.h"

namespace encore::scene {
namespace {

using testing::loadGltf;

// A triangle whose positions and indices live in meshopt-compressed views of buffer 0, with
// buffer 1 as the uri-less fallback the views nominally point to.
test::GltfBuilder compressedTriangle() {
    const float positions[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0};
    std::vector<std::uint8_t> vertexData(meshopt_encodeVertexBufferBound(3, 12));
    vertexData.resize(
        meshopt_encodeVertexBuffer(vertexData.data(), vertexData.size(), positions, 3, 12));
    const unsigned int indices[3] = {0, 1, 2};
    std::vector<std::uint8_t> indexData(meshopt_encodeIndexBufferBound(3, 3));
    indexData.resize(meshopt_encodeIndexBuffer(indexData.data(), indexData.size(), indices, 3));

    test::GltfBuilder builder;
    const auto vertexSource = builder.addBufferView(vertexData);
    const auto indexSource = builder.addBufferView(indexData);
    auto& json = builder.json();
    json["buffers"].push_back(
        {{"byteLength", 48}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    auto compressedView = [&](std::uint32_t source, std::uint32_t offset, std::uint32_t length,
                              std::uint32_t stride, const char* mode) {
        const auto& sourceView = json["bufferViews"][source];
        json["bufferViews"].push_back({{"buffer", 1},
                                       {"byteOffset", offset},
                                       {"byteLength", length},
                                       {"extensions",
                                        {{"EXT_meshopt_compression",
                                          {{"buffer", 0},
                                           {"byteOffset", sourceView["byteOffset"]},
                                           {"byteLength", sourceView["byteLength"]},
                                           {"byteStride", stride},
                                           {"count", 3},
                                           {"mode", mode}}}}}});
        return static_cast<std::uint32_t>(json["bufferViews"].size() - 1);
    };
    const auto vertexView = compressedView(vertexSource, 0, 36, 12, "ATTRIBUTES");
    json["bufferViews"][vertexView]["byteStride"] = 12;
    const auto indexView = compressedView(indexSource, 36, 12, 4, "TRIANGLES");
    const auto positionAccessor = builder.addAccessor(vertexView, 5126, 3, "VEC3");
    const auto indexAccessor = builder.addAccessor(indexView, 5125, 3, "SCALAR");
    json["extensionsUsed"] = {"EXT_meshopt_compression"};
    json["extensionsRequired"] = {"EXT_meshopt_compression"};
    builder.addMesh({.attributes = {{"POSITION", positionAccessor}}, .indices = indexAccessor});
    builder.addScene({builder.addNode({.mesh = 0u})});
    return builder;
}

TEST(MeshoptTest, CompressedViewsDecode) {
    auto scene = loadGltf(compressedTriangle());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = scene->meshes[0].primitives[0];
    EXPECT_EQ(scene->buffers[1].bytes.size(), 0u);  // The fallback stays empty.
    // Flat normals de-indexed the triangle; the decoded positions come through.
    const auto positions = scene->readFloats(*primitive.attribute(Semantic::Position));
    ASSERT_EQ(positions.size(), 3u);
    EXPECT_EQ(glm::vec3(positions[1]), glm::vec3(2, 0, 0));
    EXPECT_EQ(glm::vec3(positions[2]), glm::vec3(0, 3, 0));
    EXPECT_EQ(scene->bounds.max, glm::vec3(2, 3, 0));
}

TEST(MeshoptTest, CorruptDataIsAnError) {
    auto builder = compressedTriangle();
    std::fill(builder.bufferBytes().begin(), builder.bufferBytes().end(), 0xFF);
    testing::expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                         {"bufferView 2 (EXT_meshopt_compression)", "cannot be decoded"});
}

TEST(MeshoptTest, SourceRangePastItsBuffer) {
    auto builder = compressedTriangle();
    builder.json()["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 4096;
    testing::expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                         {"bufferView 2 (EXT_meshopt_compression)", "past the end of buffer 0"});
}

TEST(MeshoptTest, UnknownFilter) {
    auto builder = compressedTriangle();
    builder.json()["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["filter"] = "MAGIC";
    testing::expectError(loadGltf(builder), ErrorCode::Unsupported, {"MAGIC"});
}

}  // namespace
}  // namespace encore::scene
