// Every kind of bad input gets "error: <file>: <what is wrong>" on stderr, exit code 1, and no
// output image; none crashes (this suite also runs under ASan and UBSan: make test-sanitize).

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "CommandRunner.h"
#include "GltfBuilder.h"
#include "TestPaths.h"

namespace encore::test {
namespace {

// A valid indexed triangle to corrupt.
GltfBuilder triangle() {
    GltfBuilder builder;
    GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    return builder;
}

struct BadInput {
    std::string name;
    // Writes the bad file into `dir` and returns its path.
    std::function<std::filesystem::path(const std::filesystem::path& dir)> write;
    std::vector<std::string> expected;  // Substrings of the error message.
};

std::filesystem::path writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

std::filesystem::path writeBytes(const std::filesystem::path& path,
                                 const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

std::vector<BadInput> badInputs() {
    return {
        {"MissingFile", [](const auto& dir) { return dir / "absent.gltf"; }, {"does not exist"}},
        {"Directory",
         [](const auto& dir) {
             std::filesystem::create_directories(dir / "folder.gltf");
             return dir / "folder.gltf";
         },
         {"is a directory"}},
        {"InvalidJson",
         [](const auto& dir) { return writeText(dir / "a.gltf", "{\"asset\": "); },
         {"JSON is invalid"}},
        {"UnsupportedVersion",
         [](const auto& dir) {
             return writeText(dir / "a.gltf", R"({"asset": {"version": "1.0"}})");
         },
         {"version (1.0)", "not supported"}},
        {"AccessorPastBufferView",
         [](const auto& dir) {
             auto builder = triangle();
             builder.json()["accessors"][0]["count"] = 40;
             return builder.writeGltf(dir, "a");
         },
         {"accessor 0", "bufferView 0"}},
        {"BufferViewPastBuffer",
         [](const auto& dir) {
             auto builder = triangle();
             builder.json()["bufferViews"][0]["byteLength"] = 100000;
             return builder.writeGltf(dir, "a");
         },
         {"bufferView 0", "buffer 0"}},
        {"IndexOutOfRange",
         [](const auto& dir) {
             GltfBuilder builder;
             GltfBuilder::PrimitiveDesc primitive;
             primitive.attributes["POSITION"] =
                 builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
             primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 7});
             builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
             return builder.writeGltf(dir, "a");
         },
         {"index", "7", "vertex count", "3"}},
        {"ByteSizeOverflow",
         [](const auto& dir) {
             auto builder = triangle();
             builder.json()["accessors"][0]["count"] = 4294967295u;
             builder.json()["bufferViews"][0]["byteStride"] = 252;
             return builder.writeGltf(dir, "a");
         },
         {"accessor 0"}},
        {"PrimitiveWithoutPositionUnderStrict",  // Without --strict: skipped with a warning.
         [](const auto& dir) {
             auto builder = triangle();
             auto& attributes = builder.json()["meshes"][0]["primitives"][0]["attributes"];
             attributes["NORMAL"] = attributes["POSITION"];
             attributes.erase("POSITION");
             return builder.writeGltf(dir, "a");
         },
         {"POSITION"}},
        {"UnsupportedRequiredExtension",
         [](const auto& dir) {
             auto builder = triangle();
             builder.json()["extensionsUsed"] = {"KHR_materials_fancy"};
             builder.json()["extensionsRequired"] = {"KHR_materials_fancy"};
             return builder.writeGltf(dir, "a");
         },
         {"KHR_materials_fancy"}},
        {"GlbBadMagic",
         [](const auto& dir) {
             auto glb = triangle().toGlb();
             glb[0] = 'x';
             return writeBytes(dir / "a.glb", glb);
         },
         {"magic"}},
        {"GlbChunkLongerThanFile",
         [](const auto& dir) {
             auto glb = triangle().toGlb();
             glb[12] = 0xff;  // JSON chunk length, low byte.
             glb[13] = 0xff;
             return writeBytes(dir / "a.glb", glb);
         },
         {"chunk"}},
        {"MissingBufferFile",
         [](const auto& dir) {
             auto path = triangle().writeGltf(dir, "a", GltfBuilder::BufferMode::ExternalBin);
             std::filesystem::remove(dir / "a.bin");
             return path;
         },
         {"buffer 0", "a.bin"}},
        {"MissingImageUnderStrict",
         [](const auto& dir) {
             auto builder = triangle();
             const auto texture = builder.addTexture("missing.png");
             builder.json()["materials"] = {
                 {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}}};
             builder.json()["meshes"][0]["primitives"][0]["material"] = 0;
             return builder.writeGltf(dir, "a");
         },
         {"image 0", "missing.png"}},
        {"EmptyFile",
         [](const auto& dir) { return writeText(dir / "a.gltf", ""); },
         {"empty", "0 bytes"}},
        {"JsonNestedTwoHundredThousandDeep",
         [](const auto& dir) {
             return writeText(dir / "a.gltf", R"({"asset": {"version": "2.0"}, "extras": )" +
                                                  std::string(200000, '[') +
                                                  std::string(200000, ']') + "}");
         },
         {"nests", "levels deep"}},
        {"AccessorWithCountZero",
         [](const auto& dir) {
             auto builder = triangle();
             builder.json()["accessors"][1]["count"] = 0;
             return builder.writeGltf(dir, "a");
         },
         {"accessor 1 (indices of mesh 0, primitive 0)", "count 0"}},
    };
}

void PrintTo(const BadInput& input, std::ostream* out) {
    *out << input.name;
}

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, PrintsAClearErrorAndExitsWithOne) {
    const BadInput& input = GetParam();
    const auto dir = makeTempDir("bad-" + input.name);
    const auto path = input.write(dir);
    const auto output = dir / "out.png";
    const auto result =
        runEncore("render " + quote(path.string()) + " -o " + quote(output.string()) +
                  (input.name.ends_with("UnderStrict") ? " --strict" : ""));
    EXPECT_EQ(result.exitCode, 1) << result.err;
    const std::string prefix = "error: " + path.string() + ": ";
    EXPECT_EQ(result.err.rfind(prefix, 0), 0u) << "stderr: " << result.err;
    for (const auto& expected : input.expected) {
        EXPECT_NE(result.err.find(expected), std::string::npos)
            << "missing '" << expected << "' in: " << result.err;
    }
    EXPECT_FALSE(std::filesystem::exists(output));
    EXPECT_EQ(result.err.find("AddressSanitizer"), std::string::npos);
    EXPECT_EQ(result.err.find("runtime error"), std::string::npos);  // UBSan.
}

INSTANTIATE_TEST_SUITE_P(AllBadInputs,
                         BadInputTest,
                         ::testing::ValuesIn(badInputs()),
                         [](const auto& info) { return info.param.name; });

TEST(CommandLineTest, UsageErrorsExitWithTwo) {
    EXPECT_EQ(runEncore("").exitCode, 2);
    EXPECT_EQ(runEncore("render").exitCode, 2);
    EXPECT_EQ(runEncore("render x.glb --width 0").exitCode, 2);
    const auto unknown = runEncore("render x.glb --strategy fastest");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("Unknown strategy 'fastest'"), std::string::npos) << unknown.err;
}

TEST(CommandLineTest, HelpListsSubcommandsStrategiesAndExitCodes) {
    const auto help = runEncore("--help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* text : {"render", "stats", "gen", "naive", "layouts", "pipeline-cache",
                             "instancing", "materials", "bundles", "Exit codes"}) {
        EXPECT_NE(help.out.find(text), std::string::npos) << "missing " << text;
    }
}

TEST(CommandLineTest, GenRefusesAbsurdSizes) {
    const auto result = runEncore("gen --objects 0 -o /dev/null");
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("number of objects (0)"), std::string::npos) << result.err;
    EXPECT_EQ(runEncore("gen --objects 99999999 -o /dev/null").exitCode, 2);
}

}  // namespace
}  // namespace encore::test
