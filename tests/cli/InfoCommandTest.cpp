// encore info MODEL: the model summary in text and JSON, without a GPU device, and the usual
// "error: <file>: ..." with exit code 1 for bad input.

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "GltfBuilder.h"
#include "TestPaths.h"
#include "VariantFixture.h"

namespace encore::test {
namespace {

using nlohmann::json;

bool contains(const std::string& text, const std::string& fragment) {
    return text.find(fragment) != std::string::npos;
}

// Two triangles (one mesh, instanced by two nodes), a material with a shaded, required
// extension and an ignored one, a placed spot light and a placed camera.
std::filesystem::path writeShowcase(const std::filesystem::path& dir) {
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 2, 1, 3});
    const auto material = builder.addMaterial({});
    const auto mesh = builder.addMesh(
        {.attributes = {{"POSITION", positions}}, .indices = indices, .material = material});
    const auto a = builder.addNode({.mesh = mesh});
    const auto b = builder.addNode({.mesh = mesh, .translation = glm::vec3(2, 0, 0)});
    const auto light = builder.addNode({.translation = glm::vec3(0, 3, 0)});
    const auto camera = builder.addNode({.translation = glm::vec3(0, 0, 5)});
    builder.addScene({a, b, light, camera});
    auto& root = builder.json();
    root["materials"][0]["name"] = "glass";
    root["materials"][0]["extensions"] = {
        {"KHR_materials_pbrSpecularGlossiness", {{"glossinessFactor", 0.5}}},
        {"VENDOR_materials_custom", {{"factor", 1.0}}}};
    root["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness", "VENDOR_materials_custom",
                              "KHR_lights_punctual"};
    root["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
    root["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "spot"}}};
    root["nodes"][light]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
    root["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}}}}};
    root["nodes"][camera]["camera"] = 0;
    return builder.writeGltf(dir, "showcase");
}

TEST(InfoCommandTest, PrintsTheModelSummary) {
    const auto path = writeShowcase(makeTempDir("info-text"));
    const auto result = runEncore("info " + quote(path.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::string& out = result.out;
    for (const std::string& line : {
             "file: " + path.string() + "\n",
             std::string("meshes: 1\n"),
             std::string("primitives: 1\n"),
             std::string("triangles: 2 (4 drawn by the instances)\n"),
             std::string("materials: 1\n"),
             std::string("textures: 0\n"),
             std::string("images: 0\n"),
             std::string("lights: 1 (1 placed)\n"),
             std::string("cameras: 1 (1 placed)\n"),
             std::string("nodes: 4\n"),
             std::string("instances: 2\n"),
             std::string("  KHR_materials_pbrSpecularGlossiness: shaded, required\n"),
             std::string("  VENDOR_materials_custom: ignored\n"),
             std::string("  KHR_lights_punctual: shaded\n"),
             std::string("  material 0 ('glass'): VENDOR_materials_custom\n"),
             std::string("VENDOR_materials_custom, which Encore does not implement; the asset "
                         "is drawn without it."),
         }) {
        EXPECT_TRUE(contains(out, line)) << "missing '" << line << "' in:\n" << out;
    }
    // The warning is part of the summary, not printed a second time on stderr.
    EXPECT_FALSE(contains(result.err, "warning:")) << result.err;
}

TEST(InfoCommandTest, PrintsJson) {
    const auto path = writeShowcase(makeTempDir("info-json"));
    const auto result = runEncore("info " + quote(path.string()) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json report = json::parse(result.out, nullptr, false);
    ASSERT_FALSE(report.is_discarded()) << result.out;
    EXPECT_EQ(report["file"], path.string());
    const json& counts = report["counts"];
    EXPECT_EQ(counts["meshes"], 1);
    EXPECT_EQ(counts["primitives"], 1);
    EXPECT_EQ(counts["triangles"], 2);
    EXPECT_EQ(counts["drawnTriangles"], 4);
    EXPECT_EQ(counts["materials"], 1);
    EXPECT_EQ(counts["lights"], 1);
    EXPECT_EQ(counts["placedLights"], 1);
    EXPECT_EQ(counts["cameras"], 1);
    EXPECT_EQ(counts["placedCameras"], 1);
    EXPECT_EQ(counts["nodes"], 4);
    EXPECT_EQ(counts["instances"], 2);
    const json expectedExtensions = json::array(
        {{{"name", "KHR_materials_pbrSpecularGlossiness"},
          {"status", "shaded"},
          {"required", true}},
         {{"name", "VENDOR_materials_custom"}, {"status", "ignored"}, {"required", false}},
         {{"name", "KHR_lights_punctual"}, {"status", "shaded"}, {"required", false}}});
    EXPECT_EQ(report["extensions"], expectedExtensions);
    ASSERT_EQ(report["materialsWithIgnoredExtensions"].size(), 1u);
    EXPECT_EQ(report["materialsWithIgnoredExtensions"][0]["index"], 0);
    EXPECT_EQ(report["materialsWithIgnoredExtensions"][0]["name"], "glass");
    EXPECT_EQ(report["materialsWithIgnoredExtensions"][0]["ignoredExtensions"],
              json::array({"VENDOR_materials_custom"}));
    ASSERT_EQ(report["warnings"].size(), 1u);
    EXPECT_TRUE(contains(report["warnings"][0].get<std::string>(), "VENDOR_materials_custom"));
}

TEST(InfoCommandTest, GeneratedScene) {
    const auto dir = makeTempDir("info-generated");
    const auto path = dir / "generated.glb";
    ASSERT_EQ(
        runEncore("gen --objects 12 --meshes 3 --materials 5 -o " + quote(path.string())).exitCode,
        0);
    const auto result = runEncore("info --json " + quote(path.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json report = json::parse(result.out, nullptr, false);
    ASSERT_FALSE(report.is_discarded()) << result.out;
    EXPECT_EQ(report["counts"]["meshes"], 3);
    EXPECT_EQ(report["counts"]["materials"], 5);
    EXPECT_EQ(report["counts"]["instances"], 12);
    EXPECT_GT(report["counts"]["triangles"].get<std::uint64_t>(), 0u);
    EXPECT_GT(report["counts"]["drawnTriangles"].get<std::uint64_t>(),
              report["counts"]["triangles"].get<std::uint64_t>());
    EXPECT_EQ(report["counts"]["lights"], 0);
    EXPECT_TRUE(report["extensions"].empty());
    EXPECT_TRUE(report["warnings"].empty());
}

TEST(InfoCommandTest, SampleModelWithCamera) {
    const auto dir = sharedModelsDir();
    if (!dir) {
        GTEST_SKIP() << "The shared sample models (../shared/models) are absent; skipping.";
    }
    const auto result = runEncore("info " + quote((*dir / "Duck/glTF-Binary/Duck.glb").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(contains(result.out, "cameras: 1 (1 placed)\n")) << result.out;
    EXPECT_TRUE(contains(result.out, "triangles: 4212")) << result.out;
    // The chain the loader builds: level 0 is the full mesh, coarser levels follow.
    EXPECT_TRUE(contains(result.out, "(triangles per level: 4212, ")) << result.out;
    EXPECT_TRUE(contains(result.out, "extensions: none\n")) << result.out;
    EXPECT_TRUE(contains(result.out, "warnings: none\n")) << result.out;
}

// A scene without nodes is valid glTF: a warning, exit code 0, even with --strict.
TEST(InfoCommandTest, EmptySceneIsAWarning) {
    const auto dir = makeTempDir("info-empty");
    const auto path = dir / "empty.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scenes": [{}], "scene": 0})";
    const auto result = runEncore("info " + quote(path.string()));
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(contains(result.out, "draws nothing")) << result.out;
    EXPECT_TRUE(contains(result.out, "the scene it shows has no nodes")) << result.out;
}

// The specification says to skip a primitive without POSITION: a warning, not an error.
TEST(InfoCommandTest, PrimitiveWithoutPositionIsSkippedWithAWarning) {
    GltfBuilder builder;
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto mesh = builder.addMesh(std::vector<GltfBuilder::PrimitiveDesc>{
        {.attributes = {{"NORMAL", normals}}}, {.attributes = {{"POSITION", positions}}}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    const auto path = builder.writeGltf(makeTempDir("info-no-position"), "a");
    const auto result = runEncore("info " + quote(path.string()));
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(
        contains(result.out, "mesh 0, primitive 0 has no POSITION attribute; it is skipped"))
        << result.out;
}

TEST(InfoCommandTest, MissingFileIsAnError) {
    const auto path = makeTempDir("info-missing") / "absent.gltf";
    for (const char* json : {"", " --json"}) {
        const auto result = runEncore("info " + quote(path.string()) + json);
        EXPECT_EQ(result.exitCode, 1);
        EXPECT_TRUE(contains(result.err, "error: " + path.string() + ": ")) << result.err;
        EXPECT_TRUE(contains(result.err, "does not exist")) << result.err;
        EXPECT_TRUE(result.out.empty()) << result.out;
    }
}

TEST(InfoCommandTest, MalformedModelIsAnError) {
    const auto dir = makeTempDir("info-malformed");
    GltfBuilder builder;
    builder.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0}}}}};
    const auto path = builder.writeGltf(dir, "bad");
    const auto result = runEncore("info " + quote(path.string()));
    EXPECT_EQ(result.exitCode, 1);
    EXPECT_TRUE(contains(result.err, "error: " + path.string() + ": camera 0 perspective"))
        << result.err;
}

TEST(InfoCommandTest, ListsTheMaterialVariants) {
    const auto dir = makeTempDir("info-variants");
    const auto path = variantQuads().writeGlb(dir, "quads");
    const auto text = runEncore("info " + quote(path.string()));
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_TRUE(contains(text.out, "  KHR_materials_variants: shaded\n")) << text.out;
    EXPECT_TRUE(contains(text.out,
                         "material variants:\n  0: green\n  1: blue paint\n  2: glass\n"
                         "  3: textured\n"))
        << text.out;
    const auto asJson = runEncore("info --json " + quote(path.string()));
    ASSERT_EQ(asJson.exitCode, 0) << asJson.err;
    const json summary = json::parse(asJson.out);
    EXPECT_EQ(summary["variants"], json({"green", "blue paint", "glass", "textured"}));
    // Without variants: no list.
    const auto plain = runEncore("info " + quote(writeShowcase(dir).string()));
    EXPECT_FALSE(contains(plain.out, "material variants")) << plain.out;
}

// KHR_materials_diffuse_transmission is shaded: listed so, with no warning and no material
// listed as ignoring it.
TEST(InfoCommandTest, DiffuseTransmissionIsShaded) {
    const auto dir = makeTempDir("info-diffuse-transmission");
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto material = builder.addMaterial({});
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", positions}}, .material = material});
    builder.addScene({builder.addNode({.mesh = mesh})});
    builder.json()["materials"][0]["extensions"]["KHR_materials_diffuse_transmission"] = {
        {"diffuseTransmissionFactor", 0.5}};
    builder.json()["extensionsUsed"] = {"KHR_materials_diffuse_transmission"};
    const auto path = builder.writeGltf(dir, "leaf");
    const auto result = runEncore("info " + quote(path.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_TRUE(contains(result.out, "  KHR_materials_diffuse_transmission: shaded\n"))
        << result.out;
    EXPECT_FALSE(contains(result.out, "ignored")) << result.out;
    EXPECT_FALSE(contains(result.out, "does not implement")) << result.out;
    EXPECT_FALSE(contains(result.err, "warning:")) << result.err;
}

// KHR_texture_basisu: optional, info names the KTX2 images and what draws instead; required, the
// refusal names them.
TEST(InfoCommandTest, NamesTheImagesThatNeedBasisu) {
    const auto dir = makeTempDir("info-basisu");
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto texture = builder.addTexture("fallback.png");
    builder.json()["images"].push_back({{"uri", "wood.ktx2"}});
    builder.json()["images"].push_back({{"uri", "stone.ktx2"}});
    builder.json()["textures"][texture]["extensions"]["KHR_texture_basisu"] = {{"source", 1}};
    builder.json()["textures"].push_back(
        {{"extensions", {{"KHR_texture_basisu", {{"source", 2}}}}}});
    const auto material = builder.addMaterial({.baseColorTexture = texture});
    builder.json()["materials"][material]["emissiveTexture"] = {{"index", 1}};
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", positions}}, .material = material});
    builder.addScene({builder.addNode({.mesh = mesh})});
    builder.json()["extensionsUsed"] = {"KHR_texture_basisu"};
    std::ofstream(dir / "fallback.png", std::ios::binary) << "not decoded by info's check";
    const auto path = builder.writeGltf(dir, "basisu");
    const auto text = runEncore("info " + quote(path.string()));
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_TRUE(contains(text.out, "  KHR_texture_basisu: ignored\n")) << text.out;
    EXPECT_TRUE(contains(text.out,
                         "images that need KHR_texture_basisu (KTX2, not decoded: no transcoder):\n"
                         "  image 1 ('wood.ktx2'): texture 0 draws image 0 instead\n"
                         "  image 2 ('stone.ktx2'): texture 1 has no fallback (a default texture "
                         "is drawn)\n"))
        << text.out;
    const json summary = json::parse(runEncore("info --json " + quote(path.string())).out);
    ASSERT_EQ(summary["basisuImages"].size(), 2u);
    EXPECT_EQ(summary["basisuImages"][0]["image"], 1);
    EXPECT_EQ(summary["basisuImages"][0]["textures"][0]["fallbackImage"], 0);
    EXPECT_TRUE(summary["basisuImages"][1]["textures"][0]["fallbackImage"].is_null());

    builder.json()["extensionsRequired"] = {"KHR_texture_basisu"};
    const auto required = runEncore("info " + quote(builder.writeGltf(dir, "required").string()));
    EXPECT_EQ(required.exitCode, 1);
    EXPECT_TRUE(contains(required.err,
                         "required.gltf: The asset requires the extension "
                         "KHR_texture_basisu, which Encore does not support"))
        << required.err;
    EXPECT_TRUE(contains(required.err,
                         "its KTX2 images need it: image 1 ('wood.ktx2'), image 2 ('stone.ktx2')."))
        << required.err;
}

}  // namespace
}  // namespace encore::test
