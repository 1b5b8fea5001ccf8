#include "BatchCommandSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "CommandRunner.h"
#include "TestPaths.h"

namespace encore::test {

namespace fs = std::filesystem;

fs::path makeCollection(const std::string& name, int count, int objects) {
    const fs::path dir = makeTempDir(name);
    for (int i = 0; i < count; ++i) {
        const fs::path model = i < 2 ? dir / ("set" + std::to_string(i)) / "model.glb"
                                     : dir / "more" / ("scene" + std::to_string(i) + ".glb");
        fs::create_directories(model.parent_path());
        const CommandResult gen =
            runEncore("gen --objects " + std::to_string(objects) + " --seed " +
                      std::to_string(i + 1) + " -o " + quote(model.string()));
        EXPECT_EQ(gen.exitCode, 0) << gen.err;
    }
    std::ofstream(dir / "broken.gltf") << "{\"asset\": ";
    return dir;
}

GltfBuilder texturedQuad(const std::string& imageUri) {
    GltfBuilder builder;
    const std::uint32_t positions =
        builder.addPositions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
    const std::uint32_t texcoords = builder.addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const std::uint32_t indices = builder.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
    GltfBuilder::MaterialDesc material;
    material.baseColorTexture = builder.addTexture(imageUri);
    const std::uint32_t materialIndex = builder.addMaterial(material);
    const std::uint32_t mesh = builder.addMesh(
        {{{"POSITION", positions}, {"TEXCOORD_0", texcoords}}, indices, materialIndex, {}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    return builder;
}

std::vector<fs::path> filesUnder(const fs::path& dir, const std::string& extension) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (entry.is_regular_file() && entry.path().extension() == extension) {
            files.push_back(entry.path());
        }
    }
    return files;
}

std::vector<nlohmann::json> jsonLines(const fs::path& path) {
    std::vector<nlohmann::json> lines;
    std::ifstream file(path);
    for (std::string line; std::getline(file, line);) {
        lines.push_back(nlohmann::json::parse(line, nullptr, false));
    }
    return lines;
}

std::string batchArguments(const fs::path& input,
                           const fs::path& output,
                           const std::string& extra) {
    return "-v batch " + quote(input.string()) + " -o " + quote(output.string()) + " " + extra;
}

void expectUsageErrors(const fs::path& input,
                       const fs::path& output,
                       const std::string& common,
                       const std::vector<std::pair<std::string, std::string>>& cases) {
    for (const auto& [options, message] : cases) {
        const CommandResult result = runEncore(batchArguments(input, output, common + options));
        EXPECT_EQ(result.exitCode, 2) << options << ": " << result.err;
        EXPECT_NE(result.err.find(message), std::string::npos) << options << ": " << result.err;
    }
    EXPECT_TRUE(filesUnder(output, ".png").empty());
}

}  // namespace encore::test
