#include "GeneratedModels.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "GltfBuilder.h"
#include "scene/SceneGenerator.h"

namespace encore::test {

std::vector<batch::BatchInput> writeGeneratedModels(const std::filesystem::path& dir,
                                                    std::uint32_t count) {
    std::vector<batch::BatchInput> inputs;
    std::filesystem::create_directories(dir);
    for (std::uint32_t seed = 1; seed <= count; ++seed) {
        scene::GeneratorOptions generator;
        generator.objectCount = 3;
        generator.meshCount = 2;
        generator.materialCount = 2;
        generator.seed = seed;
        auto glb = scene::generateSceneGlb(generator);
        EXPECT_TRUE(glb.ok());
        if (!glb.ok()) {
            continue;
        }
        const std::filesystem::path path = dir / ("m" + std::to_string(seed) + ".glb");
        std::ofstream(path, std::ios::binary)
            .write(reinterpret_cast<const char*>(glb->data()), std::streamsize(glb->size()));
        inputs.push_back({path, "m" + std::to_string(seed)});
    }
    return inputs;
}

std::vector<std::uint8_t> cutSquareGlb(float half, float cutY) {
    GltfBuilder builder;
    const auto piece = [&](std::vector<glm::vec3> corners, std::vector<std::uint16_t> triangles,
                           glm::vec4 color) {
        const auto normals =
            builder.addNormals(std::vector<glm::vec3>(corners.size(), {0.0f, 0.0f, 1.0f}));
        const auto positions = builder.addPositions(corners);
        const auto indices = builder.addIndices<std::uint16_t>(triangles);
        const auto material = builder.addMaterial({.baseColor = color});
        return builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                                .indices = indices,
                                .material = material});
    };
    const auto below = piece({{-half, -half, 0.0f}, {half, -half, 0.0f}, {half, cutY, 0.0f}},
                             {0, 1, 2}, {0.9f, 0.1f, 0.1f, 1.0f});
    const auto above =
        piece({{-half, -half, 0.0f}, {half, cutY, 0.0f}, {half, half, 0.0f}, {-half, half, 0.0f}},
              {0, 1, 2, 0, 2, 3}, {0.1f, 0.2f, 0.9f, 1.0f});
    std::vector<std::uint32_t> nodes;
    nodes.push_back(builder.addNode({.mesh = below, .name = "below"}));
    nodes.push_back(builder.addNode({.name = "empty"}));
    nodes.push_back(builder.addNode({.name = "empty too"}));
    nodes.push_back(builder.addNode({.mesh = above, .name = "above"}));
    builder.addScene(nodes);
    return builder.toGlb();
}

}  // namespace encore::test
