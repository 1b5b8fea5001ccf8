#include <gtest/gtest.h>

#include <map>
#include <regex>

#include "shaders/EmbeddedFiles.h"
#include "shaders/ShaderComposer.h"
#include "shaders/ShaderLibrary.h"
#include "shaders/VertexLocations.h"

namespace encore::shaders {
namespace {

using Flags = std::set<std::string, std::less<>>;

Result<std::string> compose(const std::map<std::string, std::string>& files, const Flags& flags) {
    FileLookup lookup = [&](std::string_view name) -> std::optional<std::string_view> {
        auto found = files.find(std::string(name));
        if (found == files.end()) {
            return std::nullopt;
        }
        return found->second;
    };
    return composeShader("main.wgsl", flags, lookup);
}

TEST(ShaderComposerTest, KeepsLinesOfTakenBranchesOnly) {
    const std::map<std::string, std::string> files = {
        {"main.wgsl", "a\n#if X\nb\n#elif Y\nc\n#else\nd\n#endif\ne"}};
    EXPECT_EQ(*compose(files, {"X"}), "a\nb\ne\n");
    EXPECT_EQ(*compose(files, {"Y"}), "a\nc\ne\n");
    EXPECT_EQ(*compose(files, {"X", "Y"}), "a\nb\ne\n");
    EXPECT_EQ(*compose(files, {}), "a\nd\ne\n");
}

TEST(ShaderComposerTest, NestsAndNegates) {
    const std::map<std::string, std::string> files = {
        {"main.wgsl", "#if A\n#if !B\nab\n#else\nAB\n#endif\n#else\n#if B\nnever\n#endif\n#endif"}};
    EXPECT_EQ(*compose(files, {"A"}), "ab\n");
    EXPECT_EQ(*compose(files, {"A", "B"}), "AB\n");
    EXPECT_EQ(*compose(files, {"B"}), "never\n");
    EXPECT_EQ(*compose(files, {}), "");
}

TEST(ShaderComposerTest, IncludesOnceAndOnlyInActiveBranches) {
    const std::map<std::string, std::string> files = {
        {"main.wgsl",
         "#include \"lib.wgsl\"\n#include \"lib.wgsl\"\n#if X\n#include \"x.wgsl\"\n#endif\nmain"},
        {"lib.wgsl", "lib"},
        {"x.wgsl", "x"}};
    EXPECT_EQ(*compose(files, {}), "lib\nmain\n");
    EXPECT_EQ(*compose(files, {"X"}), "lib\nx\nmain\n");
}

TEST(ShaderComposerTest, ReportsErrorsWithFileAndLine) {
    auto missing = compose({{"main.wgsl", "ok\n#include \"nope.wgsl\""}}, {});
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("'nope.wgsl' does not exist"), std::string::npos);

    auto unbalanced = compose({{"main.wgsl", "#if X\na"}}, {});
    ASSERT_FALSE(unbalanced.ok());
    EXPECT_NE(unbalanced.error().message.find("#if without #endif"), std::string::npos);

    auto stray = compose({{"main.wgsl", "a\n#endif"}}, {});
    ASSERT_FALSE(stray.ok());
    EXPECT_NE(stray.error().message.find("line 2: #endif without #if"), std::string::npos);

    auto expression = compose({{"main.wgsl", "#if A && B\n#endif"}}, {});
    ASSERT_FALSE(expression.ok());
    EXPECT_NE(expression.error().message.find("not a flag name"), std::string::npos);

    auto unknown = compose({{"main.wgsl", "#define X"}}, {});
    ASSERT_FALSE(unknown.ok());
    EXPECT_NE(unknown.error().message.find("unknown directive '#define'"), std::string::npos);

    auto afterElse = compose({{"main.wgsl", "#if X\n#else\n#else\n#endif"}}, {});
    ASSERT_FALSE(afterElse.ok());
}

TEST(ShaderComposerTest, EveryMeshVariantComposes) {
    for (int bits = 0; bits < 48; ++bits) {
        ShaderVariantKey key;
        key.instanceSource = (bits & 32)  ? InstanceSource::VisibleList
                             : (bits & 1) ? InstanceSource::InstanceStorage
                                          : InstanceSource::NodeUniform;
        key.materials = bits & 2;
        key.hasTexcoord = bits & 4;
        key.hasColor = bits & 8;
        key.alphaMask = bits & 16;
        auto source = composeEmbeddedShader("mesh.wgsl", key.flags());
        ASSERT_TRUE(source.ok()) << source.error().message;
        EXPECT_EQ(source->find('#'), std::string::npos) << "directive left in " << key.describe();
        EXPECT_NE(source->find("fn vertexMain"), std::string::npos);
    }
}

// The C++ location table and the WGSL declarations must agree, for every vertex input (the
// flags below declare them all).
TEST(ShaderComposerTest, VertexLocationsMatchTheWgsl) {
    Flags all = {"HAS_TEXCOORD", "HAS_COLOR", "HAS_TANGENT", "HAS_TEXCOORD1",
                 "SKINNED",      "SKINNED_8", "ANIMATED"};
    auto source = composeEmbeddedShader("mesh.wgsl", all);
    ASSERT_TRUE(source.ok());
    const std::map<std::string, std::uint32_t> expected = {
        {"position", kPositionLocation},  {"normal", kNormalLocation},
        {"texcoord", kTexcoord0Location}, {"color", kColor0Location},
        {"tangent", kTangentLocation},    {"texcoord1", kTexcoord1Location},
        {"joints0", kJoints0Location},    {"weights0", kWeights0Location},
        {"joints1", kJoints1Location},    {"weights1", kWeights1Location}};
    const auto inputStart = source->find("struct VertexInput");
    const auto inputEnd = source->find('}', inputStart);
    const std::string input = source->substr(inputStart, inputEnd - inputStart);
    std::regex declaration(R"(@location\((\d+)\)\s+(\w+)\s*:)");
    std::size_t found = 0;
    for (std::sregex_iterator it(input.begin(), input.end(), declaration), end; it != end; ++it) {
        const std::string name = (*it)[2];
        ASSERT_TRUE(expected.contains(name)) << "unexpected vertex input " << name;
        EXPECT_EQ(std::stoul((*it)[1]), expected.at(name)) << name;
        ++found;
    }
    EXPECT_EQ(found, expected.size());
}

TEST(ShaderVariantKeyTest, HashAndEqualityFollowEveryField) {
    ShaderVariantKey a;
    ShaderVariantKey b;
    EXPECT_EQ(a, b);
    EXPECT_EQ(ShaderVariantKeyHash{}(a), ShaderVariantKeyHash{}(b));
    b.alphaMask = true;
    EXPECT_NE(a, b);
    EXPECT_EQ(b.describe(), "ALPHA_MASK");
}

}  // namespace
}  // namespace encore::shaders
