// Accessor handling: strides, sparse and zero materialisation, vertex format legalisation, index
// widening, and the containers (data: uris, external files, GLB).

#include <gtest/gtest.h>

#include <fstream>

#include "SceneTestUtils.h"
#include "TestPaths.h"

namespace encore::scene {
namespace {

using testing::loadGlb;
using testing::loadGltf;
using testing::triangleBuilder;

const Primitive& firstPrimitive(const SceneData& scene) {
    return scene.meshes.at(0).primitives.at(0);
}

TEST(AccessorTest, AbsentByteStrideMeansTightlyPacked) {
    auto scene = loadGltf(triangleBuilder());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Accessor& positions = scene->accessors[0];
    EXPECT_EQ(positions.byteStride, 12u);
    EXPECT_EQ(scene->bufferViews[positions.view.index()].byteStride, 0u);
    EXPECT_EQ(scene->accessorBytes(AccessorId(0u)).size(), 36u);
}

TEST(AccessorTest, InterleavedStrideIsKept) {
    test::GltfBuilder builder;
    // Position (12 bytes) and normal (12 bytes) interleaved with stride 24.
    std::vector<float> interleaved;
    const float data[3][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {0, 1, 0, 0, 0, 1}};
    for (const auto& vertex : data) {
        interleaved.insert(interleaved.end(), vertex, vertex + 6);
    }
    std::vector<std::uint8_t> bytes(interleaved.size() * 4);
    std::memcpy(bytes.data(), interleaved.data(), bytes.size());
    const auto view = builder.addBufferView(bytes, 24);
    const auto positions = builder.addAccessor(view, 5126, 3, "VEC3", 0);
    const auto normals = builder.addAccessor(view, 5126, 3, "VEC3", 12);
    builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}}});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = firstPrimitive(*scene);
    // Legal as they are: no copies.
    EXPECT_EQ(primitive.attribute(Semantic::Position)->value, positions);
    EXPECT_EQ(primitive.attribute(Semantic::Normal)->value, normals);
    EXPECT_EQ(scene->accessors[normals].byteStride, 24u);
    const auto values = scene->readFloats(AccessorId(normals));
    ASSERT_EQ(values.size(), 3u);
    EXPECT_EQ(values[1], glm::vec4(0, 0, 1, 1));
    EXPECT_EQ(scene->packedAccessorBytes(AccessorId(normals)).size(), 36u);
}

TEST(AccessorTest, NormalizedU8x3IsRepackedToFourComponents) {
    auto builder = triangleBuilder();
    const auto colors = builder.addAccessor(
        std::vector<std::uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 255}, "VEC3", {.normalized = true});
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = colors;
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        builder.addAccessor(std::vector<std::int16_t>{0, 0, 32767, 0, 0, 32767}, "VEC2",
                            {.normalized = true, .byteStride = 4});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = firstPrimitive(*scene);
    const Accessor& color = scene->accessors[primitive.attribute(Semantic::Color0)->index()];
    EXPECT_NE(primitive.attribute(Semantic::Color0)->value, colors);
    EXPECT_EQ(color.componentType, ComponentType::Uint8);
    EXPECT_EQ(color.componentCount, 4);
    EXPECT_TRUE(color.normalized);
    EXPECT_EQ(color.byteStride, 4u);
    const auto values = scene->readFloats(*primitive.attribute(Semantic::Color0));
    EXPECT_EQ(values[1], glm::vec4(0, 1, 0, 1));  // Missing alpha reads as opaque.
    // i16x2 normalized with stride 4 is a WebGPU format already: kept.
    const Accessor& uv = scene->accessors[primitive.attribute(Semantic::Texcoord0)->index()];
    EXPECT_EQ(uv.componentType, ComponentType::Int16);
    EXPECT_EQ(uv.componentCount, 2);
}

TEST(AccessorTest, NormalizedI8x3NormalIsPaddedWithZero) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = builder.addAccessor(
        std::vector<std::int8_t>{0, 0, 127, 0, 0, 127, 0, 0, 127}, "VEC3", {.normalized = true});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto id = *firstPrimitive(*scene).attribute(Semantic::Normal);
    const Accessor& normal = scene->accessors[id.index()];
    EXPECT_EQ(normal.componentCount, 4);
    EXPECT_EQ(normal.componentType, ComponentType::Int8);
    const auto packed = scene->packedAccessorBytes(id);
    ASSERT_EQ(packed.size(), 12u);
    EXPECT_EQ(packed[3], 0);
    EXPECT_EQ(packed[2], 127);
}

TEST(AccessorTest, QuantizedI16PositionsBecomeFloat) {
    test::GltfBuilder builder;
    const auto positions =
        builder.addAccessor(std::vector<std::int16_t>{0, 0, 0, 100, 0, 0, 0, 100, 0}, "VEC3",
                            {.byteStride = 8, .minMax = true});
    builder.json()["extensionsRequired"] = {"KHR_mesh_quantization"};
    builder.json()["extensionsUsed"] = {"KHR_mesh_quantization"};
    builder.addMesh({.attributes = {{"POSITION", positions}}});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto id = *firstPrimitive(*scene).attribute(Semantic::Position);
    ASSERT_NE(id.value, positions);  // Flat normals de-index, so the copy is a gathered one.
    const Accessor& position = scene->accessors[id.index()];
    EXPECT_EQ(position.componentType, ComponentType::Float32);
    EXPECT_EQ(position.componentCount, 3);
    const auto values = scene->readFloats(id);
    ASSERT_EQ(values.size(), 3u);
    EXPECT_EQ(glm::vec3(values[1]), glm::vec3(100, 0, 0));
    EXPECT_EQ(firstPrimitive(*scene).bounds.max, glm::vec3(100, 100, 0));
}

TEST(AccessorTest, SparseWithBaseView) {
    auto builder = triangleBuilder();
    const auto indices = builder.addBufferView(std::vector<std::uint8_t>{2, 0, 0, 0});
    std::vector<std::uint8_t> values(12);
    const float replacement[3] = {5, 6, 7};
    std::memcpy(values.data(), replacement, 12);
    const auto valueView = builder.addBufferView(values);
    builder.json()["accessors"][0]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", indices}, {"componentType", 5121}}},
        {"values", {{"bufferView", valueView}}}};
    builder.json()["accessors"][0].erase("min");
    builder.json()["accessors"][0].erase("max");
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto floats = scene->readFloats(AccessorId(0u));
    ASSERT_EQ(floats.size(), 3u);
    EXPECT_EQ(glm::vec3(floats[0]), glm::vec3(0, 0, 0));
    EXPECT_EQ(glm::vec3(floats[1]), glm::vec3(1, 0, 0));
    EXPECT_EQ(glm::vec3(floats[2]), glm::vec3(5, 6, 7));
    // Materialised: its view is a new one after the asset's own.
    EXPECT_GE(scene->accessors[0].view.index(), 3u);
    EXPECT_EQ(firstPrimitive(*scene).bounds.max, glm::vec3(5, 6, 7));
}

TEST(AccessorTest, SparseWithoutBaseViewStartsFromZeros) {
    auto builder = triangleBuilder();
    const auto indices = builder.addBufferView(std::vector<std::uint8_t>{1, 0, 0, 0});
    std::vector<std::uint8_t> values(12);
    const float replacement[3] = {1, 2, 3};
    std::memcpy(values.data(), replacement, 12);
    const auto valueView = builder.addBufferView(values);
    builder.json()["accessors"].push_back(
        {{"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"},
         {"sparse",
          {{"count", 1},
           {"indices", {{"bufferView", indices}, {"componentType", 5123}}},
           {"values", {{"bufferView", valueView}}}}}});
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 1;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto floats = scene->readFloats(*firstPrimitive(*scene).attribute(Semantic::Normal));
    ASSERT_EQ(floats.size(), 3u);
    EXPECT_EQ(glm::vec3(floats[0]), glm::vec3(0));
    EXPECT_EQ(glm::vec3(floats[1]), glm::vec3(1, 2, 3));
}

TEST(AccessorTest, AccessorWithoutBufferViewIsZeros) {
    auto builder = triangleBuilder();
    builder.json()["accessors"].push_back(
        {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 1;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const auto id = *firstPrimitive(*scene).attribute(Semantic::Normal);
    EXPECT_TRUE(scene->accessors[id.index()].view.valid());
    for (const auto& value : scene->readFloats(id)) {
        EXPECT_EQ(glm::vec3(value), glm::vec3(0));
    }
}

TEST(AccessorTest, U8IndicesAreWidenedToU16) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const auto indices = builder.addIndices(std::vector<std::uint8_t>{0, 1, 2});
    builder.addMesh(
        {.attributes = {{"POSITION", positions}, {"NORMAL", normals}}, .indices = indices});
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& primitive = firstPrimitive(*scene);
    ASSERT_TRUE(primitive.indices);
    const Accessor& accessor = scene->accessors[primitive.indices->index()];
    EXPECT_EQ(accessor.componentType, ComponentType::Uint16);
    EXPECT_EQ(accessor.byteStride, 2u);
    EXPECT_EQ(scene->readIndices(*primitive.indices), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(AccessorTest, TightU16AndU32IndicesAreKept) {
    for (bool wide : {false, true}) {
        test::GltfBuilder builder;
        const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
        const auto indices = wide ? builder.addIndices(std::vector<std::uint32_t>{2, 1, 0})
                                  : builder.addIndices(std::vector<std::uint16_t>{2, 1, 0});
        builder.addMesh(
            {.attributes = {{"POSITION", positions}, {"NORMAL", normals}}, .indices = indices});
        // The accessor as the converter keeps it, before mesh optimisation rewrites indices.
        LoadOptions options;
        options.optimizeMeshes = false;
        options.buildLevelsOfDetail = false;
        auto scene = loadGltf(builder, options);
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        EXPECT_EQ(firstPrimitive(*scene).indices->value, indices);
    }
}

TEST(AccessorTest, DataUriGltfAndGlbLoadTheSame) {
    auto builder = triangleBuilder();
    auto fromGltf = loadGltf(builder);
    auto fromGlb = loadGlb(builder);
    ASSERT_TRUE(fromGltf.ok()) << fromGltf.error().message;
    ASSERT_TRUE(fromGlb.ok()) << fromGlb.error().message;
    EXPECT_EQ(fromGlb->buffers[0].name, "GLB BIN chunk");
    EXPECT_EQ(fromGltf->buffers[0].bytes, fromGlb->buffers[0].bytes);
    EXPECT_EQ(fromGltf->instances.size(), fromGlb->instances.size());
    EXPECT_EQ(fromGltf->bounds.max, fromGlb->bounds.max);
}

TEST(AccessorTest, ExternalBinWithPercentEncodedName) {
    const auto dir = test::makeTempDir("scene-external");
    auto builder = triangleBuilder();
    builder.writeGltf(dir, "my model", test::GltfBuilder::BufferMode::ExternalBin);
    // Rewrite the uri percent-encoded, as exporters do for spaces.
    auto json = nlohmann::json::parse(std::ifstream(dir / "my model.gltf"));
    json["buffers"][0]["uri"] = "my%20model.bin";
    std::ofstream(dir / "encoded.gltf") << json.dump();
    auto scene = loadScene(dir / "encoded.gltf");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->buffers[0].name, "my%20model.bin");
    EXPECT_EQ(scene->sourcePath, dir / "encoded.gltf");
}

TEST(AccessorTest, GlbFileRoundTrip) {
    const auto dir = test::makeTempDir("scene-glb");
    const auto path = triangleBuilder().writeGlb(dir, "triangle");
    auto scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->instances.size(), 1u);
    EXPECT_EQ(scene->bounds.max, glm::vec3(1, 1, 0));
}

TEST(AccessorTest, NonBase64DataUri) {
    auto builder = triangleBuilder();
    // Percent-encoded payload: 36 zero bytes.
    std::string uri = "data:application/octet-stream,";
    for (int i = 0; i < 36; ++i) {
        uri += "%00";
    }
    builder.json()["buffers"][0]["uri"] = uri;
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->buffers[0].bytes, std::vector<std::uint8_t>(36, 0));
}

TEST(AccessorTest, MatrixAccessorsDoNotBreakLoading) {
    auto builder = triangleBuilder();
    const glm::mat4 identity(1.0f);
    std::vector<float> values(&identity[0][0], &identity[0][0] + 16);
    const auto matrices = builder.addAccessor(values, "MAT4");
    builder.json()["skins"] = {{{"inverseBindMatrices", matrices}, {"joints", {0}}}};
    builder.json()["animations"] = {
        {{"channels", nlohmann::json::array()}, {"samplers", nlohmann::json::array()}}};
    builder.json()["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->accessors[matrices].componentCount, 16);
}

}  // namespace
}  // namespace encore::scene
