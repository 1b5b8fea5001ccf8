// Corrupted assets never crash the loader: seeded byte flips and truncations of valid .glb files
// (generated, built in code, and sample models when present) must each load or fail with an
// error naming the file. Run under ASan and UBSan (make test-sanitize), an out-of-bounds read or
// undefined behaviour on any of them fails the suite.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <random>

#include "GltfBuilder.h"
#include "TestPaths.h"
#include "encore/scene/SceneData.h"
#include "scene/SceneGenerator.h"

namespace encore::scene {
namespace {

std::vector<std::uint8_t> readBytes(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), {}};
}

std::vector<std::pair<std::string, std::vector<std::uint8_t>>> validAssets() {
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> assets;
    GeneratorOptions generated;
    generated.objectCount = 4;
    generated.meshCount = 3;
    assets.emplace_back("generated.glb", *generateSceneGlb(generated));

    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 0}, {1, 0}, {0, 1}});
    primitive.indices = builder.addIndices<std::uint8_t>({0, 1, 2});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    assets.emplace_back("triangle.glb", builder.toGlb());

    if (const auto dir = test::sharedModelsDir()) {
        for (const char* model : {"BoxInterleaved/glTF-Binary/BoxInterleaved.glb",
                                  "MeshoptPirate/glTF-Meshopt/pirate.glb",
                                  "OrientationTest/glTF-Binary/OrientationTest.glb",
                                  "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb"}) {
            auto bytes = readBytes(*dir / model);
            if (!bytes.empty()) {
                assets.emplace_back(model, std::move(bytes));
            }
        }
    }
    return assets;
}

// ENCORE_CORRUPTION_MUTATIONS raises the count for longer hunts (CI runs the default).
int mutationsPerAsset() {
    if (const char* text = std::getenv("ENCORE_CORRUPTION_MUTATIONS")) {
        return std::max(1, std::atoi(text));
    }
    return 150;
}

TEST(CorruptionTest, CorruptedGlbFilesLoadOrFailCleanly) {
    std::mt19937 random(20261121);
    LoadOptions options;
    options.decodeImages = false;  // Image decoding is stb's; the loader's own parsing is tested.
    std::size_t loaded = 0;
    std::size_t failed = 0;
    for (const auto& [name, valid] : validAssets()) {
        ASSERT_TRUE(loadSceneFromMemory(valid, {}, name, options).ok()) << name;
        for (int mutation = 0; mutation < mutationsPerAsset(); ++mutation) {
            std::vector<std::uint8_t> bytes = valid;
            std::uniform_int_distribution<std::size_t> position(0, bytes.size() - 1);
            if (mutation % 10 == 0) {
                bytes.resize(position(random));  // Truncated.
            } else {
                const int flips = 1 + mutation % 4;
                for (int flip = 0; flip < flips; ++flip) {
                    bytes[position(random)] ^= static_cast<std::uint8_t>(1u << (random() % 8));
                }
            }
            auto scene = loadSceneFromMemory(bytes, {}, name, options);
            if (scene.ok()) {
                ++loaded;
            } else {
                ++failed;
                EXPECT_EQ(scene.error().message.rfind(name + ": ", 0), 0u)
                    << "errors name the file: " << scene.error().message;
            }
        }
    }
    // Both outcomes occur: flips in unused bytes load, flips in the structure fail.
    EXPECT_GT(loaded, 0u);
    EXPECT_GT(failed, 0u);
}

}  // namespace
}  // namespace encore::scene
