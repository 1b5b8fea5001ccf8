// Bad input must fail with the right ErrorCode and a message naming the file, the element and the
// numbers involved; it must never crash (these tests also run under ASan/UBSan).

#include <gtest/gtest.h>

#include "SceneTestUtils.h"
#include "TestPaths.h"

namespace encore::scene {
namespace {

using testing::expectError;
using testing::loadGlb;
using testing::loadGltf;
using testing::loadText;
using testing::triangleBuilder;

TEST(LoaderErrorTest, MissingFileNamesThePath) {
    auto result = loadScene("/nonexistent/encore/model.gltf");
    expectError(result, ErrorCode::FileNotFound, {"/nonexistent/encore/model.gltf", "not exist"});
}

TEST(LoaderErrorTest, DirectoryIsUnreadable) {
    const auto dir = test::makeTempDir("scene-dir");
    auto result = loadScene(dir);
    expectError(result, ErrorCode::FileUnreadable, {dir.string(), "directory"});
}

TEST(LoaderErrorTest, InvalidJsonGivesThePosition) {
    auto result = loadText("{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [ }\n");
    expectError(result, ErrorCode::InvalidFormat, {"test.gltf: ", "JSON is invalid", "line 3"});
}

TEST(LoaderErrorTest, JsonThatIsNotAnObject) {
    expectError(loadText("[1, 2, 3]"), ErrorCode::InvalidFormat, {"test.gltf: ", "not an object"});
}

TEST(LoaderErrorTest, MissingAsset) {
    expectError(loadText("{\"nodes\": []}"), ErrorCode::InvalidFormat, {"'asset'"});
}

TEST(LoaderErrorTest, UnsupportedVersion) {
    expectError(loadText(R"({"asset": {"version": "1.0"}})"), ErrorCode::Unsupported,
                {"test.gltf: ", "version (1.0)"});
}

TEST(LoaderErrorTest, AssetVersionOfWrongType) {
    expectError(loadText(R"({"asset": {"version": 2}})"), ErrorCode::InvalidFormat,
                {"asset", "'version'"});
}

TEST(LoaderErrorTest, UnsupportedRequiredExtension) {
    auto builder = triangleBuilder();
    builder.json()["extensionsRequired"] = {"KHR_materials_volume_magic"};
    builder.json()["extensionsUsed"] = {"KHR_materials_volume_magic"};
    expectError(loadGltf(builder), ErrorCode::Unsupported, {"KHR_materials_volume_magic"});
}

TEST(LoaderErrorTest, UnknownUsedExtensionIsIgnored) {
    auto builder = triangleBuilder();
    builder.json()["extensionsUsed"] = {"KHR_materials_volume_magic"};
    EXPECT_TRUE(loadGltf(builder).ok());
}

TEST(LoaderErrorTest, AccessorPastItsBufferView) {
    auto builder = triangleBuilder();
    builder.json()["accessors"][0]["count"] = 4;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"test.gltf: accessor 0 (POSITION of mesh 0, primitive 0)",
                 "past the end of bufferView 0", "offset 0 + 48 bytes > length 36"});
}

TEST(LoaderErrorTest, AccessorOffsetPastItsBufferView) {
    auto builder = triangleBuilder();
    builder.json()["accessors"][0]["byteOffset"] = 4;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"offset 4 + 36 bytes > length 36"});
}

TEST(LoaderErrorTest, BufferViewPastItsBuffer) {
    auto builder = triangleBuilder();
    builder.json()["bufferViews"][0]["byteLength"] = 1000;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"bufferView 0", "buffer 0", "1000", "36 bytes"});
}

TEST(LoaderErrorTest, BufferViewOffsetOverflow) {
    auto builder = triangleBuilder();
    builder.json()["bufferViews"][0]["byteOffset"] = 18446744073709551600ull;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"bufferView 0", "buffer 0"});
}

TEST(LoaderErrorTest, InvalidByteStride) {
    auto builder = triangleBuilder();
    builder.json()["bufferViews"][0]["byteStride"] = 6;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"bufferView 0", "byteStride (6"});
}

TEST(LoaderErrorTest, HugeCountWithHugeStrideIsLimitExceeded) {
    auto builder = triangleBuilder();
    builder.json()["bufferViews"][0]["byteStride"] = 252;
    builder.json()["accessors"][0]["count"] = 4294967295u;
    builder.json()["accessors"][0]["type"] = "VEC4";
    expectError(loadGltf(builder), ErrorCode::LimitExceeded, {"accessor 0", "4294967295"});
}

TEST(LoaderErrorTest, CountBeyond32BitsIsLimitExceeded) {
    auto builder = triangleBuilder();
    builder.json()["accessors"][0]["count"] = 9223372036854775807ull;
    expectError(loadGltf(builder), ErrorCode::LimitExceeded, {"accessor 0", "9223372036854775807"});
}

TEST(LoaderErrorTest, CountLargerThanTheBufferIsInvalid) {
    auto builder = triangleBuilder();
    builder.json()["accessors"][0]["count"] = 1000;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"accessor 0", "12000 bytes"});
}

TEST(LoaderErrorTest, HugeAccessorWithoutBufferView) {
    auto builder = triangleBuilder();
    builder.json()["accessors"].push_back(
        {{"componentType", 5126}, {"count", 100000000}, {"type", "VEC4"}});
    expectError(loadGltf(builder), ErrorCode::LimitExceeded,
                {"accessor 1", "100000000 x 16 bytes", "1 GiB"});
}

TEST(LoaderErrorTest, IndexValueOutOfRange) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 5});
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", positions}}, .indices = indices});
    builder.addScene({builder.addNode({.mesh = mesh})});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0", "index value 5", "position 2", "vertex count (3)"});
}

TEST(LoaderErrorTest, PrimitiveWithoutPositionIsAnErrorWhenStrict) {
    // Without --strict it is skipped with a warning (SpecificationEdgeCaseTest).
    test::GltfBuilder builder;
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    builder.addMesh({.attributes = {{"NORMAL", normals}}});
    expectError(loadGltf(builder, {.strict = true}), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0", "no POSITION"});
}

TEST(LoaderErrorTest, AttributesOfDifferentLengths) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}});
    builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}}});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0", "different lengths", "3", "2"});
}

TEST(LoaderErrorTest, UnknownMode) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["mode"] = 7;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"mesh 0, primitive 0", "mode (7)"});
}

TEST(LoaderErrorTest, MeshReferencesMissingAccessor) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0 refers to accessor 99", "1 accessor"});
}

TEST(LoaderErrorTest, NodeReferencesMissingMesh) {
    auto builder = triangleBuilder();
    builder.json()["nodes"][0]["mesh"] = 7;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"node 0 refers to mesh 7"});
}

TEST(LoaderErrorTest, TextureReferencesMissingImage) {
    auto builder = triangleBuilder();
    builder.json()["textures"] = {{{"source", 5}}};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"texture 0 refers to image 5", "0 images"});
}

TEST(LoaderErrorTest, SceneReferencesMissingNode) {
    auto builder = triangleBuilder();
    builder.json()["scenes"][0]["nodes"] = {0, 12};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"scene 0 refers to node 12"});
}

TEST(LoaderErrorTest, MaterialReferencesMissingTexture) {
    auto builder = triangleBuilder();
    builder.addMaterial({.baseColorTexture = 3});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"material 0 baseColorTexture refers to texture 3"});
}

TEST(LoaderErrorTest, WrongJsonTypeNamesTheElement) {
    auto builder = triangleBuilder();
    builder.json()["accessors"][0]["count"] = "three";
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"accessor 0", "'count'", "\"three\""});
}

TEST(LoaderErrorTest, WrongJsonTypesElsewhere) {
    const std::vector<std::pair<std::string, nlohmann::json>> edits = {
        {"/meshes/0/primitives", nlohmann::json("none")},
        {"/nodes/0/translation", nlohmann::json({1, 2})},
        {"/nodes/0/children", nlohmann::json({-1})},
        {"/accessors/0", nlohmann::json(5)},
        {"/scenes/0/nodes", nlohmann::json({{"a", 1}})},
        {"/buffers/0/byteLength", nlohmann::json(nullptr)},
        {"/meshes/0/primitives/0/attributes/POSITION", nlohmann::json(-3)},
        {"/accessors/0/componentType", nlohmann::json(1234)},
        {"/accessors/0/type", nlohmann::json("VEC7")},
        {"/scene", nlohmann::json(1.5)},
    };
    for (const auto& [pointer, value] : edits) {
        auto builder = triangleBuilder();
        builder.json()[nlohmann::json::json_pointer(pointer)] = value;
        auto result = loadGltf(builder);
        ASSERT_FALSE(result.ok()) << pointer;
        EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat) << result.error().message;
        EXPECT_EQ(result.error().message.rfind("test.gltf: ", 0), 0u) << result.error().message;
    }
}

TEST(LoaderErrorTest, NodeWithTwoParents) {
    auto builder = triangleBuilder();
    builder.addNode({.children = {0}});
    builder.addNode({.children = {0}});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"node 0 has two parents", "node 1", "node 2"});
}

TEST(LoaderErrorTest, NodeCycle) {
    auto builder = triangleBuilder();
    builder.json()["nodes"][0]["children"] = {1};
    builder.addNode({.children = {0}});
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"cycle"});
}

TEST(LoaderErrorTest, GlbWithBadMagic) {
    std::vector<std::uint8_t> bytes = triangleBuilder().toGlb();
    bytes[0] = 'X';
    auto result = loadSceneFromMemory(bytes, "/nonexistent", "bad.glb");
    expectError(result, ErrorCode::InvalidFormat, {"bad.glb: ", "magic"});
}

TEST(LoaderErrorTest, GlbChunkLongerThanTheFile) {
    std::vector<std::uint8_t> bytes = triangleBuilder().toGlb();
    bytes[12] = 0xFF;  // JSON chunk length, low byte.
    bytes[13] = 0xFF;
    auto result = loadSceneFromMemory(bytes, "/nonexistent", "bad.glb");
    expectError(result, ErrorCode::InvalidFormat, {"chunk 0", "past the end of the file"});
}

TEST(LoaderErrorTest, GlbHeaderLengthLongerThanTheFile) {
    std::vector<std::uint8_t> bytes = triangleBuilder().toGlb();
    bytes[10] = 0x10;
    auto result = loadSceneFromMemory(bytes, "/nonexistent", "bad.glb");
    expectError(result, ErrorCode::InvalidFormat, {"header's length", "does not match"});
}

TEST(LoaderErrorTest, GlbWithoutJsonChunk) {
    const std::vector<std::uint8_t> bytes = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 12, 0, 0, 0};
    auto result = loadSceneFromMemory(bytes, "/nonexistent", "empty.glb");
    expectError(result, ErrorCode::InvalidFormat, {"empty.glb: ", "no JSON chunk"});
}

TEST(LoaderErrorTest, GlbTruncatedEverywhere) {
    // Every prefix of a valid GLB must fail cleanly (or, for the whole file, load).
    const std::vector<std::uint8_t> bytes = triangleBuilder().toGlb();
    for (std::size_t size = 0; size < bytes.size(); ++size) {
        auto result = loadSceneFromMemory(std::span(bytes).first(size), "/nonexistent", "t.glb");
        EXPECT_FALSE(result.ok()) << size;
    }
}

TEST(LoaderErrorTest, GlbVersion1) {
    std::vector<std::uint8_t> bytes = triangleBuilder().toGlb();
    bytes[4] = 1;
    expectError(loadSceneFromMemory(bytes, "/nonexistent", "old.glb"), ErrorCode::Unsupported,
                {"version (1)"});
}

TEST(LoaderErrorTest, MissingBufferFile) {
    const auto dir = test::makeTempDir("scene-missing-bin");
    const auto path =
        triangleBuilder().writeGltf(dir, "model", test::GltfBuilder::BufferMode::ExternalBin);
    std::filesystem::remove(dir / "model.bin");
    expectError(loadScene(path), ErrorCode::FileNotFound,
                {path.string() + ": ", "buffer 0 ('model.bin')", "does not exist"});
}

TEST(LoaderErrorTest, BufferShorterThanItsByteLength) {
    auto builder = triangleBuilder();
    builder.json()["buffers"][0]["byteLength"] = 100;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"buffer 0", "36 bytes < 100"});
}

TEST(LoaderErrorTest, InvalidBase64) {
    auto builder = triangleBuilder();
    builder.json()["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAA*AAA=";
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"buffer 0", "base64"});
}

TEST(LoaderErrorTest, RemoteUriIsUnsupported) {
    auto builder = triangleBuilder();
    builder.json()["buffers"][0]["uri"] = "https://example.com/model.bin";
    expectError(loadGltf(builder), ErrorCode::Unsupported, {"buffer 0", "https://example.com"});
}

TEST(LoaderErrorTest, GarbageDracoData) {
    auto builder = triangleBuilder();
    const std::vector<std::uint8_t> garbage(64, 0x5A);
    const auto view = builder.addBufferView(garbage);
    builder.json()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    builder.json()["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}}}};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"mesh 0, primitive 0", "cannot be decoded by Draco"});
}

TEST(LoaderErrorTest, SparseIndexOutOfRange) {
    auto builder = triangleBuilder();
    const auto indices = builder.addBufferView(std::vector<std::uint8_t>{7, 0, 0, 0});
    const auto values = builder.addBufferView(std::vector<std::uint8_t>(12, 0));
    builder.json()["accessors"][0]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", indices}, {"componentType", 5121}}},
        {"values", {{"bufferView", values}}}};
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"accessor 0", "sparse index 7", "count 3"});
}

TEST(LoaderErrorTest, StrictModeMakesMissingImagesErrors) {
    auto builder = triangleBuilder();
    const auto texture = builder.addTexture("missing.png");
    builder.json()["meshes"][0]["primitives"][0]["material"] =
        builder.addMaterial({.baseColorTexture = texture});
    expectError(loadGltf(builder, {.strict = true}), ErrorCode::FileNotFound,
                {"image 0 ('missing.png')", "missing.png"});
}

}  // namespace
}  // namespace encore::scene
