#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.h"
#include "encore/batch/BatchInputs.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

// Discovery never opens the models: empty files stand for them.
void touch(const fs::path& path) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "";
}

std::vector<std::string> namesOf(const std::vector<BatchInput>& inputs) {
    std::vector<std::string> names;
    for (const BatchInput& input : inputs) {
        names.push_back(input.name);
    }
    return names;
}

TEST(BatchInputsTest, FolderIsSearchedRecursivelyAndNamesKeepTheFolders) {
    const fs::path dir = test::makeTempDir("batch-inputs-folder");
    touch(dir / "b" / "model.glb");
    touch(dir / "a" / "model.glb");
    touch(dir / "a" / "deeper" / "Car.GLTF");
    touch(dir / "top.gltf");
    touch(dir / "a" / "model.bin");
    touch(dir / "notes.txt");
    auto inputs = discoverInputs(dir);
    ASSERT_TRUE(inputs.ok()) << inputs.error().message;
    EXPECT_EQ(namesOf(*inputs),
              (std::vector<std::string>{"a/deeper/Car", "a/model", "b/model", "top"}));
    EXPECT_EQ((*inputs)[1].path, dir / "a" / "model.glb");
}

TEST(BatchInputsTest, SameNameWithDifferentExtensionsKeepsTheExtensions) {
    const fs::path dir = test::makeTempDir("batch-inputs-extensions");
    touch(dir / "x.gltf");
    touch(dir / "x.glb");
    touch(dir / "y.glb");
    auto inputs = discoverInputs(dir);
    ASSERT_TRUE(inputs.ok());
    EXPECT_EQ(namesOf(*inputs), (std::vector<std::string>{"x.glb", "x.gltf", "y"}));
}

TEST(BatchInputsTest, TextListResolvesAgainstItsFolderFromTheCommonRoot) {
    const fs::path dir = test::makeTempDir("batch-inputs-text");
    touch(dir / "models" / "one" / "model.glb");
    touch(dir / "models" / "two" / "model.glb");
    std::ofstream(dir / "list.txt")
        << "# a comment\nmodels/one/model.glb\n\n  "
        << (dir / "models" / "two" / "model.glb").string() << "  \nmodels/one/model.glb\n";
    auto inputs = discoverInputs(dir / "list.txt");
    ASSERT_TRUE(inputs.ok()) << inputs.error().message;
    EXPECT_EQ(namesOf(*inputs), (std::vector<std::string>{"one/model", "two/model"}));
    EXPECT_EQ((*inputs)[0].path, dir / "models" / "one" / "model.glb");
}

TEST(BatchInputsTest, ListedPathsAreNamedFromTheirCommonFolderOncePerFile) {
    const fs::path dir = test::makeTempDir("batch-inputs-listed");
    const std::vector<fs::path> paths = {dir / "set" / "b" / "model.glb",
                                         dir / "set" / "a" / "x.gltf",
                                         dir / "set" / "a" / ".." / "b" / "model.glb"};
    auto inputs = listedInputs(paths);
    ASSERT_TRUE(inputs.ok()) << inputs.error().message;
    EXPECT_EQ(namesOf(*inputs), (std::vector<std::string>{"b/model", "a/x"}));
    EXPECT_EQ((*inputs)[0].path, dir / "set" / "b" / "model.glb");
    EXPECT_FALSE(listedInputs({}).ok());
}

TEST(BatchInputsTest, JsonListOfPaths) {
    const fs::path dir = test::makeTempDir("batch-inputs-json");
    std::ofstream(dir / "list.json") << R"(["glbs/000-001/abc.glb", "glbs/000-002/def.glb"])";
    auto inputs = discoverInputs(dir / "list.json");
    ASSERT_TRUE(inputs.ok()) << inputs.error().message;
    EXPECT_EQ(namesOf(*inputs), (std::vector<std::string>{"000-001/abc", "000-002/def"}));
}

TEST(BatchInputsTest, JsonThatIsNotAListOfStringsIsRefused) {
    const fs::path dir = test::makeTempDir("batch-inputs-bad-json");
    std::ofstream(dir / "object.json") << R"({"a": 1})";
    std::ofstream(dir / "numbers.json") << "[1, 2]";
    for (const char* name : {"object.json", "numbers.json"}) {
        auto inputs = discoverInputs(dir / name);
        ASSERT_FALSE(inputs.ok()) << name;
        EXPECT_EQ(inputs.error().code, ErrorCode::InvalidFormat);
        EXPECT_NE(inputs.error().message.find(name), std::string::npos);
    }
}

TEST(BatchInputsTest, SingleModel) {
    const fs::path dir = test::makeTempDir("batch-inputs-single");
    touch(dir / "Duck.glb");
    auto inputs = discoverInputs(dir / "Duck.glb");
    ASSERT_TRUE(inputs.ok());
    EXPECT_EQ(namesOf(*inputs), (std::vector<std::string>{"Duck"}));
}

TEST(BatchInputsTest, MissingInputAndEmptyFolderFail) {
    const fs::path dir = test::makeTempDir("batch-inputs-missing");
    auto missing = discoverInputs(dir / "absent");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::FileNotFound);
    auto empty = discoverInputs(dir);
    ASSERT_FALSE(empty.ok());
    EXPECT_EQ(empty.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(empty.error().message.find("no .gltf or .glb"), std::string::npos);
}

TEST(BatchInputsTest, ModelPathsByExtension) {
    EXPECT_TRUE(isModelPath("a/b.glb"));
    EXPECT_TRUE(isModelPath("B.GLTF"));
    EXPECT_FALSE(isModelPath("a.bin"));
    EXPECT_FALSE(isModelPath("glb"));
}

}  // namespace
}  // namespace encore::batch
