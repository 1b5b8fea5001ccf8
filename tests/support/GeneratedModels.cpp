#include "GeneratedModels.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

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

}  // namespace encore::test
