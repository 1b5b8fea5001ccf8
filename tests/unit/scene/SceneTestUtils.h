#pragma once

// Shared helpers of the scene unit tests: load a GltfBuilder asset from memory and check errors.

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "GltfBuilder.h"
#include "encore/scene/SceneData.h"

namespace encore::scene::testing {

inline Result<SceneData> loadGltf(const test::GltfBuilder& builder,
                                  const LoadOptions& options = {},
                                  const std::filesystem::path& baseDirectory = "/nonexistent") {
    const auto bytes = builder.toGltfBytes();
    return loadSceneFromMemory(bytes, baseDirectory, "test.gltf", options);
}

inline Result<SceneData> loadGlb(const test::GltfBuilder& builder,
                                 const LoadOptions& options = {}) {
    const auto bytes = builder.toGlb();
    return loadSceneFromMemory(bytes, "/nonexistent", "test.glb", options);
}

inline Result<SceneData> loadText(const std::string& text, const std::string& name = "test.gltf") {
    const std::vector<std::uint8_t> bytes(text.begin(), text.end());
    return loadSceneFromMemory(bytes, "/nonexistent", name);
}

// Asserts the load failed with `code` and a message containing every fragment.
inline void expectError(const Result<SceneData>& result,
                        ErrorCode code,
                        std::initializer_list<std::string> fragments) {
    ASSERT_FALSE(result.ok()) << "the load succeeded but should have failed";
    EXPECT_EQ(result.error().code, code)
        << errorCodeName(result.error().code) << ": " << result.error().message;
    for (const std::string& fragment : fragments) {
        EXPECT_NE(result.error().message.find(fragment), std::string::npos)
            << "missing '" << fragment << "' in: " << result.error().message;
    }
}

// A builder holding one triangle (mesh 0, node 0, scene 0) with positions as accessor 0.
inline test::GltfBuilder triangleBuilder() {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const auto mesh = builder.addMesh({.attributes = {{"POSITION", positions}}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    return builder;
}

// A triangle whose primitive uses material 0, and `textures` textures without images (so no
// missing-image warnings get in the way): for material extension tests.
inline test::GltfBuilder materialBuilder(int textures = 4) {
    auto builder = triangleBuilder();
    builder.json()["meshes"][0]["primitives"][0]["material"] = builder.addMaterial({});
    for (int i = 0; i < textures; ++i) {
        builder.json()["textures"].push_back(nlohmann::json::object());
    }
    return builder;
}

}  // namespace encore::scene::testing
