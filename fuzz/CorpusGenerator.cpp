// Writes the generated part of the fuzzing seed corpus into a directory (argument 1): small
// documents built with tests/support/GltfBuilder that cover the loader's features, the bad
// inputs of tests/cli/BadInputTest.cpp. Each document is written as .gltf (JSON, buffer as a
// data: uri) and as .glb. make-corpus.sh runs it.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "GltfBuilder.h"

namespace encore::fuzz {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

// A 1x1 RGBA PNG.
constexpr const char* kPngUri =
    "data:image/"
    "png;base64,"
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg"
    "==";

void writeBytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The bad inputs' valid starting point: an indexed triangle.
GltfBuilder triangle() {
    GltfBuilder builder;
    GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    return builder;
}

GltfBuilder attributes() {
    GltfBuilder builder;
    GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] =
        builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    primitive.attributes["NORMAL"] =
        builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 0}, {1, 0}, {0, 1}, {1, 1}});
    primitive.attributes["COLOR_0"] =
        builder.addColors({{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}});
    primitive.attributes["TEXCOORD_1"] = builder.addAccessor<std::uint8_t>(
        {0, 0, 255, 0, 0, 255, 255, 255}, "VEC2", {.normalized = true});
    primitive.attributes["TANGENT"] = builder.addAccessor<float>(
        {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", {.byteStride = 20});
    primitive.indices = builder.addIndices<std::uint8_t>({0, 1, 2, 2, 1, 3});
    primitive.material = builder.addMaterial({.baseColorTexture = builder.addTexture(kPngUri)});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    return builder;
}

GltfBuilder quantized() {
    GltfBuilder builder;
    builder.json()["extensionsUsed"] = {"KHR_mesh_quantization"};
    builder.json()["extensionsRequired"] = {"KHR_mesh_quantization"};
    GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addAccessor<std::int16_t>(
        {0, 0, 0, 100, 0, 0, 0, 100, 0}, "VEC3", {.minMax = true});
    primitive.attributes["NORMAL"] = builder.addAccessor<std::int8_t>(
        {0, 0, 127, 0, 0, 127, 0, 0, 127}, "VEC3", {.normalized = true});
    primitive.attributes["TEXCOORD_0"] =
        builder.addAccessor<std::uint16_t>({0, 0, 1, 0, 0, 1}, "VEC2");
    builder.addScene(
        {builder.addNode({.mesh = builder.addMesh(primitive), .scale = glm::vec3(0.01f)})});
    return builder;
}

GltfBuilder topologies() {
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    std::vector<GltfBuilder::PrimitiveDesc> primitives;
    for (std::uint32_t mode = 0; mode <= 6; ++mode) {
        primitives.push_back({.attributes = {{"POSITION", positions}}, .mode = mode});
    }
    primitives.push_back({.attributes = {{"POSITION", positions}},
                          .indices = builder.addIndices<std::uint32_t>({0, 1, 2, 3}),
                          .mode = 6});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitives, "modes")})});
    return builder;
}

GltfBuilder sparseAndZeroAccessors() {
    GltfBuilder builder = triangle();
    const auto indices = builder.addBufferView(std::vector<std::uint8_t>{1, 0, 2, 0});
    const auto values = builder.addBufferView(std::vector<std::uint8_t>(24, 0x3f));
    builder.json()["accessors"][0]["sparse"] = {
        {"count", 2},
        {"indices", {{"bufferView", indices}, {"componentType", 5123}}},
        {"values", {{"bufferView", values}}}};
    // An accessor without a bufferView (all zeros) used as NORMAL.
    builder.json()["accessors"].push_back(
        {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    builder.json()["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        builder.json()["accessors"].size() - 1;
    return builder;
}

GltfBuilder sceneGraph() {
    GltfBuilder builder;
    const auto mesh = builder.addMesh(
        {.attributes = {{"POSITION", builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}});
    const auto leaf = builder.addNode({.mesh = mesh, .translation = glm::vec3(1, 2, 3)});
    const auto mirrored = builder.addNode({.mesh = mesh, .scale = glm::vec3(-1, 1, 1)});
    const auto matrix = builder.addNode(
        {.mesh = mesh, .children = {leaf, mirrored}, .matrix = glm::mat4(2.0f), .name = "root"});
    const auto rotated =
        builder.addNode({.mesh = mesh, .rotation = glm::quat(0.7071f, 0.0f, 0.7071f, 0.0f)});
    const auto instanced = builder.addNode({.mesh = mesh});
    const auto translations = builder.addAccessor<float>({0, 0, 0, 5, 0, 0, 0, 5, 0}, "VEC3");
    const auto rotations = builder.addAccessor<float>({0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0}, "VEC4");
    const auto scales = builder.addAccessor<float>({1, 1, 1, 2, 2, 2, 1, 0, 1}, "VEC3");
    builder.json()["nodes"][instanced]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
        {"TRANSLATION", translations}, {"ROTATION", rotations}, {"SCALE", scales}};
    builder.json()["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    builder.addScene({matrix, rotated, instanced});
    builder.addScene({leaf});
    builder.json()["scene"] = 1;
    return builder;
}

GltfBuilder lightsAndCameras() {
    GltfBuilder builder = triangle();
    builder.json()["extensionsUsed"] = {"KHR_lights_punctual"};
    builder.json()["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "directional"}, {"color", {1, 0.9, 0.8}}, {"intensity", 3}},
        {{"type", "point"}, {"range", 10}, {"name", "bulb"}},
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}}};
    builder.json()["cameras"] = {
        {{"type", "perspective"},
         {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"zfar", 100}, {"aspectRatio", 1.5}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.01}}}},
        {{"type", "orthographic"},
         {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 50}}}}};
    auto& nodes = builder.json()["nodes"];
    for (int i = 0; i < 3; ++i) {
        nodes.push_back({{"camera", i}, {"translation", {0, 0, 5 + i}}});
        nodes.push_back({{"extensions", {{"KHR_lights_punctual", {{"light", i}}}}},
                         {"rotation", {0, 0.7071, 0, 0.7071}}});
    }
    builder.json()["scenes"][0]["nodes"] = {0, 1, 2, 3, 4, 5, 6};
    return builder;
}

GltfBuilder materials() {
    GltfBuilder builder;
    const auto texture = builder.addTexture(kPngUri, builder.addSampler(9728, 9987, 33071, 33648));
    const auto texture2 = builder.addTexture(kPngUri, builder.addSampler({}, 9729));
    const Json ref = {{"index", texture},
                      {"texCoord", 1},
                      {"extensions",
                       {{"KHR_texture_transform",
                         {{"offset", {0.5, 0}}, {"rotation", 0.3}, {"scale", {2, 2}}}}}}};
    const Json ref2 = {{"index", texture2}};
    builder.json()["extensionsUsed"] = {
        "KHR_texture_transform",      "KHR_materials_specular",
        "KHR_materials_clearcoat",    "KHR_materials_sheen",
        "KHR_materials_ior",          "KHR_materials_emissive_strength",
        "KHR_materials_unlit",        "KHR_materials_pbrSpecularGlossiness",
        "KHR_materials_transmission", "KHR_materials_volume"};
    Json materialList = Json::array();
    materialList.push_back({{"name", "metal-rough"},
                            {"pbrMetallicRoughness",
                             {{"baseColorFactor", {1, 0.5, 0.5, 0.8}},
                              {"baseColorTexture", ref},
                              {"metallicFactor", 0.2},
                              {"roughnessFactor", 0.7},
                              {"metallicRoughnessTexture", ref2}}},
                            {"normalTexture", {{"index", texture}, {"scale", 0.5}}},
                            {"occlusionTexture", {{"index", texture2}, {"strength", 0.3}}},
                            {"emissiveTexture", ref2},
                            {"emissiveFactor", {1, 1, 0}},
                            {"alphaMode", "MASK"},
                            {"alphaCutoff", 0},
                            {"doubleSided", true},
                            {"extensions",
                             {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}},
                              {"KHR_materials_ior", {{"ior", 1.3}}},
                              {"KHR_materials_specular",
                               {{"specularFactor", 0.5},
                                {"specularTexture", ref2},
                                {"specularColorFactor", {1, 0, 0}},
                                {"specularColorTexture", ref}}},
                              {"KHR_materials_clearcoat",
                               {{"clearcoatFactor", 1},
                                {"clearcoatTexture", ref2},
                                {"clearcoatRoughnessFactor", 0.1},
                                {"clearcoatRoughnessTexture", ref2},
                                {"clearcoatNormalTexture", {{"index", texture}, {"scale", 2}}}}},
                              {"KHR_materials_sheen",
                               {{"sheenColorFactor", {1, 1, 1}},
                                {"sheenColorTexture", ref},
                                {"sheenRoughnessFactor", 0.5},
                                {"sheenRoughnessTexture", ref2}}},
                              {"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                              {"KHR_materials_volume", {{"thicknessFactor", 1}}}}}});
    materialList.push_back({{"name", "unlit"},
                            {"alphaMode", "BLEND"},
                            {"pbrMetallicRoughness", {{"baseColorTexture", ref2}}},
                            {"extensions", {{"KHR_materials_unlit", Json::object()}}}});
    materialList.push_back({{"name", "spec-gloss"},
                            {"extensions",
                             {{"KHR_materials_pbrSpecularGlossiness",
                               {{"diffuseFactor", {1, 1, 1, 1}},
                                {"diffuseTexture", ref2},
                                {"specularFactor", {0.5, 0.5, 0.5}},
                                {"glossinessFactor", 0.3},
                                {"specularGlossinessTexture", ref}}}}}});
    std::vector<GltfBuilder::PrimitiveDesc> primitives;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto texcoords = builder.addTexcoords({{0, 0}, {1, 0}, {0, 1}});
    for (std::uint32_t i = 0; i < 4; ++i) {
        GltfBuilder::PrimitiveDesc primitive{.attributes = {{"POSITION", positions},
                                                            {"TEXCOORD_0", texcoords},
                                                            {"TEXCOORD_1", texcoords}}};
        if (i < 3) {
            primitive.material = i;
        }
        primitives.push_back(primitive);
    }
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitives)})});
    builder.json()["materials"] = materialList;
    return builder;
}

// A 2x1 lossless WebP image (libwebp's WebPEncodeLosslessRGBA, one pixel half transparent).
constexpr const char* kWebpUri =
    "data:image/webp;base64,UklGRiAAAABXRUJQVlA4TBMAAAAvAQAAEA9QoPnf//8BhoOM6H8AAA==";

// KHR_materials_variants on two primitives, and textures with EXT_texture_webp (a WebP image and
// a PNG fallback) and KHR_texture_basisu (a KTX2 image never read).
GltfBuilder variantsAndTextures() {
    GltfBuilder builder;
    const auto texture = builder.addTexture(kPngUri);
    auto& json = builder.json();
    json["images"].push_back({{"uri", kWebpUri}, {"mimeType", "image/webp"}});
    json["images"].push_back({{"uri", "never-read.ktx2"}, {"mimeType", "image/ktx2"}});
    json["textures"][texture]["extensions"] = {{"EXT_texture_webp", {{"source", 1}}},
                                               {"KHR_texture_basisu", {{"source", 2}}}};
    json["textures"].push_back({{"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}});
    const auto plain = builder.addMaterial({});
    const auto textured = builder.addMaterial({.baseColorTexture = texture});
    const auto blended = builder.addMaterial({.alphaMode = "BLEND", .baseColorTexture = 1u});
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto texcoords = builder.addTexcoords({{0, 0}, {1, 0}, {0, 1}});
    std::vector<GltfBuilder::PrimitiveDesc> primitives(
        2, {.attributes = {{"POSITION", positions}, {"TEXCOORD_0", texcoords}}, .material = plain});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitives)})});
    auto& mesh = json["meshes"][0]["primitives"];
    mesh[0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", textured}, {"variants", {0, 2}}}, {{"material", blended}, {"variants", {1}}}};
    mesh[1]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", blended}, {"variants", {2}}, {"name", "glass"}}};
    json["extensions"]["KHR_materials_variants"]["variants"] = {
        {{"name", "textured"}}, {{"name", "blended"}}, {{"name", "both"}}};
    json["extensionsUsed"] = {"KHR_materials_variants", "EXT_texture_webp", "KHR_texture_basisu"};
    return builder;
}

struct Document {
    std::string name;
    std::function<GltfBuilder()> build;
};

std::vector<Document> documents() {
    return {{"triangle", triangle},
            {"attributes", attributes},
            {"quantized", quantized},
            {"topologies", topologies},
            {"sparse", sparseAndZeroAccessors},
            {"scene-graph", sceneGraph},
            {"lights-cameras", lightsAndCameras},
            {"materials", materials},
            {"variants-textures", variantsAndTextures}};
}

// tests/cli/BadInputTest.cpp's inputs (those that are a file's contents).
std::vector<std::pair<std::string, std::vector<std::uint8_t>>> badInputs() {
    auto text = [](const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
    auto edited = [](const std::function<void(Json&)>& edit) {
        auto builder = triangle();
        edit(builder.json());
        return builder.toGltfBytes();
    };
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> inputs;
    inputs.emplace_back("invalid-json.gltf", text("{\"asset\": "));
    inputs.emplace_back("unsupported-version.gltf", text(R"({"asset": {"version": "1.0"}})"));
    inputs.emplace_back("accessor-past-view.gltf",
                        edited([](Json& json) { json["accessors"][0]["count"] = 40; }));
    inputs.emplace_back("view-past-buffer.gltf",
                        edited([](Json& json) { json["bufferViews"][0]["byteLength"] = 100000; }));
    {
        GltfBuilder builder;
        GltfBuilder::PrimitiveDesc primitive;
        primitive.attributes["POSITION"] = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 7});
        builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
        inputs.emplace_back("index-out-of-range.gltf", builder.toGltfBytes());
    }
    inputs.emplace_back("byte-size-overflow.gltf", edited([](Json& json) {
                            json["accessors"][0]["count"] = 4294967295u;
                            json["bufferViews"][0]["byteStride"] = 252;
                        }));
    inputs.emplace_back("primitive-without-position.gltf", edited([](Json& json) {
                            auto& attributes = json["meshes"][0]["primitives"][0]["attributes"];
                            attributes["NORMAL"] = attributes["POSITION"];
                            attributes.erase("POSITION");
                        }));
    inputs.emplace_back("unsupported-required-extension.gltf", edited([](Json& json) {
                            json["extensionsUsed"] = {"KHR_materials_fancy"};
                            json["extensionsRequired"] = {"KHR_materials_fancy"};
                        }));
    auto glb = triangle().toGlb();
    glb[0] = 'x';
    inputs.emplace_back("glb-bad-magic.glb", glb);
    glb = triangle().toGlb();
    glb[12] = 0xff;
    glb[13] = 0xff;
    inputs.emplace_back("glb-chunk-longer-than-file.glb", glb);
    inputs.emplace_back("missing-buffer-file.gltf",
                        edited([](Json& json) { json["buffers"][0]["uri"] = "a.bin"; }));
    {
        auto builder = triangle();
        const auto texture = builder.addTexture("missing.png");
        builder.json()["materials"] = {
            {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}}};
        builder.json()["meshes"][0]["primitives"][0]["material"] = 0;
        inputs.emplace_back("missing-image.gltf", builder.toGltfBytes());
    }
    return inputs;
}

}  // namespace
}  // namespace encore::fuzz

int main(int argc, char** argv) {
    using namespace encore;
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    int count = 0;
    for (const auto& document : fuzz::documents()) {
        const auto builder = document.build();
        fuzz::writeBytes(dir / ("gen-" + document.name + ".gltf"), builder.toGltfBytes());
        fuzz::writeBytes(dir / ("gen-" + document.name + ".glb"), builder.toGlb());
        count += 2;
    }
    for (const auto& [name, bytes] : fuzz::badInputs()) {
        fuzz::writeBytes(dir / ("bad-" + name), bytes);
        ++count;
    }
    std::printf("%d generated seed files in %s\n", count, dir.c_str());
    return 0;
}
