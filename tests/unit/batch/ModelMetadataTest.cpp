// metadata.json's facts: counts as drawn, the images that could not be read, extensions, bounds
// before normalisation and the file's SHA-256, from tiny built files, a generated scene and
// shared models (skipped when absent); blank views from coverage counts.

#include <gtest/gtest.h>

#include <fstream>

#include "GltfBuilder.h"
#include "TestPaths.h"
#include "batch/ModelMetadata.h"
#include "core/FileIO.h"
#include "core/Sha256.h"
#include "scene/SceneGenerator.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

// A quad (two indexed triangles) placed twice, a triangle strip of four vertices (two triangles)
// and three points, a texture whose image is missing, and an extension Encore does not shade.
// With normals, so that the loader keeps the vertices as they are.
fs::path writeCountedModel(const fs::path& dir) {
    test::GltfBuilder builder;
    const std::vector<glm::vec3> up(4, glm::vec3(0, 0, 1));
    const auto quadPositions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const auto quadIndices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    const auto texture = builder.addTexture("missing.png");
    const auto material = builder.addMaterial({.baseColorTexture = texture});
    const auto quad = builder.addMesh(
        {.attributes = {{"POSITION", quadPositions}, {"NORMAL", builder.addNormals(up)}},
         .indices = quadIndices,
         .material = material});
    const auto stripPositions = builder.addPositions({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1, 1, 3}});
    const auto pointPositions = builder.addPositions({{-1, -1, -1}, {2, 2, 2}, {0, 0, 0}});
    const auto mixed = builder.addMesh(std::vector<test::GltfBuilder::PrimitiveDesc>{
        {.attributes = {{"POSITION", stripPositions}, {"NORMAL", builder.addNormals(up)}},
         .mode = 5},
        {.attributes = {{"POSITION", pointPositions}}, .mode = 0}});
    builder.addScene({builder.addNode({.mesh = quad}),
                      builder.addNode({.mesh = quad, .translation = glm::vec3(4, 0, 0)}),
                      builder.addNode({.mesh = mixed})});
    builder.json()["extensionsUsed"] = {"VENDOR_materials_custom"};
    builder.json()["materials"][0]["extensions"] = {{"VENDOR_materials_custom", {{"factor", 0.5}}}};
    return builder.writeGlb(dir, "counted");
}

TEST(ModelMetadataTest, CountsWhatIsDrawnAndWhatFailed) {
    const fs::path path = writeCountedModel(test::makeTempDir("metadata-counted"));
    ModelFacts facts;
    auto scene = loadModelFile(path, {}, facts);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->sourcePath, path);
    EXPECT_EQ(facts.fileBytes, fs::file_size(path));
    auto bytes = readFile(path);
    ASSERT_TRUE(bytes.ok());
    EXPECT_EQ(facts.sha256, Sha256::hex(*bytes));
    EXPECT_EQ(facts.sha256.size(), 64u);

    EXPECT_EQ(facts.triangles, 2u * 2 + 2);  // The quad twice, the strip's two, no points.
    EXPECT_EQ(facts.vertices, 4u * 2 + 4 + 3);
    EXPECT_EQ(facts.meshes, 2u);
    EXPECT_EQ(facts.primitives, 3u);
    EXPECT_EQ(facts.instances, 3u);
    EXPECT_EQ(facts.nodes, 3u);
    EXPECT_EQ(facts.materials, 1u);  // The default one the strip and points get is not the file's.
    EXPECT_EQ(facts.textures, 1u);
    EXPECT_EQ(facts.images, 1u);
    ASSERT_EQ(facts.imagesFailed.size(), 1u);
    EXPECT_EQ(facts.imagesFailed[0].index, 0u);
    EXPECT_EQ(facts.imagesFailed[0].name, "missing.png");
    EXPECT_NE(facts.imagesFailed[0].error.find("missing.png"), std::string::npos)
        << facts.imagesFailed[0].error;
    EXPECT_EQ(facts.extensionsUsed, std::vector<std::string>{"VENDOR_materials_custom"});
    EXPECT_EQ(facts.extensionsIgnored, std::vector<std::string>{"VENDOR_materials_custom"});
    EXPECT_EQ(facts.warnings.size(), 2u);  // The image and the extension.
    EXPECT_EQ(facts.bounds.min, glm::vec3(-1.0f));
    EXPECT_EQ(facts.bounds.max, glm::vec3(5.0f, 2.0f, 3.0f));
    EXPECT_TRUE(facts.animations.empty());

    const BatchInput input{path, "set/counted"};
    const nlohmann::json json = metadataJson(input, facts, {.load = 0.25, .render = 0.5}, 4, {}, 1);
    EXPECT_EQ(json["file"], path.string());
    EXPECT_EQ(json["name"], "set/counted");
    EXPECT_EQ(json["sha256"], facts.sha256);
    EXPECT_EQ(json["triangles"], 6);
    EXPECT_EQ(json["imagesFailed"][0]["name"], "missing.png");
    EXPECT_EQ(json["extensionsIgnored"][0], "VENDOR_materials_custom");
    EXPECT_EQ(json["bounds"]["max"], nlohmann::json::parse("[5.0, 2.0, 3.0]"));
    EXPECT_EQ(json["views"], 4);
    EXPECT_TRUE(json["blankViews"].is_null()) << "coverage not counted";
    EXPECT_EQ(json["seconds"]["load"], 0.25);
    EXPECT_EQ(json["seconds"]["render"], 0.5);
}

TEST(ModelMetadataTest, LoadErrorsAreTheLoadersOwn) {
    const fs::path dir = test::makeTempDir("metadata-errors");
    std::ofstream(dir / "broken.gltf") << "{\"asset\": ";
    for (const fs::path& path : {dir / "broken.gltf", dir / "absent.glb"}) {
        ModelFacts facts;
        auto loaded = loadModelFile(path, {}, facts);
        auto reference = scene::loadScene(path);
        ASSERT_FALSE(loaded.ok());
        ASSERT_FALSE(reference.ok());
        EXPECT_EQ(loaded.error().message, reference.error().message);
        EXPECT_EQ(loaded.error().code, reference.error().code);
    }
    // --strict: the missing image fails the model as loadScene fails it.
    const fs::path counted = writeCountedModel(dir);
    ModelFacts facts;
    auto strict = loadModelFile(counted, {.strict = true}, facts);
    ASSERT_FALSE(strict.ok());
    EXPECT_EQ(strict.error().message, scene::loadScene(counted, {.strict = true}).error().message);
}

TEST(ModelMetadataTest, AGeneratedScene) {
    scene::GeneratorOptions generator;
    generator.objectCount = 12;
    generator.meshCount = 3;
    generator.materialCount = 4;
    generator.textures = true;
    auto glb = scene::generateSceneGlb(generator);
    ASSERT_TRUE(glb.ok());
    const fs::path path = test::makeTempDir("metadata-generated") / "generated.glb";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb->data()), std::streamsize(glb->size()));
    ModelFacts facts;
    auto scene = loadModelFile(path, {}, facts);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(facts.sha256, Sha256::hex(*glb));
    EXPECT_EQ(facts.instances, 12u);
    EXPECT_EQ(facts.meshes, 3u);
    EXPECT_EQ(facts.materials, 4u);
    EXPECT_GT(facts.textures, 0u);
    EXPECT_TRUE(facts.imagesFailed.empty());
    EXPECT_TRUE(facts.warnings.empty());
    EXPECT_GT(facts.triangles, facts.instances);
    EXPECT_GT(facts.vertices, facts.instances);
    EXPECT_FALSE(facts.bounds.empty());
}

// Shared models whose contents are known: BoxTextured's 12 triangles on 24 vertices with one
// texture, and the Fox's three animations.
TEST(ModelMetadataTest, SharedModels) {
    const auto models = test::sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "../shared/models is absent";
    }
    ModelFacts box;
    auto boxScene =
        loadModelFile(*models / "BoxTextured" / "glTF-Binary" / "BoxTextured.glb", {}, box);
    ASSERT_TRUE(boxScene.ok()) << boxScene.error().message;
    EXPECT_EQ(box.triangles, 12u);
    EXPECT_EQ(box.vertices, 24u);
    EXPECT_EQ(box.materials, 1u);
    EXPECT_EQ(box.textures, 1u);
    EXPECT_EQ(box.images, 1u);
    EXPECT_TRUE(box.imagesFailed.empty());

    ModelFacts fox;
    auto foxScene = loadModelFile(*models / "Fox" / "glTF-Binary" / "Fox.glb", {}, fox);
    ASSERT_TRUE(foxScene.ok()) << foxScene.error().message;
    ASSERT_EQ(fox.animations.size(), 3u);
    EXPECT_EQ(fox.animations[0].name, "Survey");
    EXPECT_EQ(fox.animations[1].name, "Walk");
    EXPECT_EQ(fox.animations[2].name, "Run");
    for (const auto& animation : fox.animations) {
        EXPECT_GT(animation.seconds, 0.5f) << animation.name;
        EXPECT_GT(animation.channels, 0u) << animation.name;
    }
    EXPECT_EQ(fox.skins, 1u);
}

TEST(ModelMetadataTest, BlankViewsHaveFewerCoveredPixelsThanTheThreshold) {
    const std::vector<std::uint8_t> pixels = {9, 9,   9, 0, 9, 9, 9, 1, 9, 9,
                                              9, 255, 0, 0, 0, 0, 0, 0, 0, 128};
    EXPECT_EQ(coveredPixels(pixels), 3u);
    EXPECT_EQ(coveredPixels({}), 0u);
    const std::vector<std::uint64_t> covered = {0, 5, 100, 4};
    EXPECT_EQ(blankViews(covered, 1), (std::vector<std::uint32_t>{0}));
    EXPECT_EQ(blankViews(covered, 5), (std::vector<std::uint32_t>{0, 3}));
    EXPECT_TRUE(blankViews(covered, 0).empty());
    const nlohmann::json json = metadataJson({"m.glb", "m"}, {}, {}, 4, covered, 5);
    EXPECT_EQ(json["blankViews"], nlohmann::json::parse("[0, 3]"));
    EXPECT_EQ(json["coveredPixels"], nlohmann::json::parse("[0, 5, 100, 4]"));
    EXPECT_EQ(json["blankThreshold"], 5);
}

}  // namespace
}  // namespace encore::batch
