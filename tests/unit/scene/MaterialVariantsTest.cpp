// KHR_materials_variants in the loader: the root's variant names, each primitive's mappings
// (sorted, the default material kept), finding a variant by name or index with errors that list
// the variants, the checks on bad mappings, and reading the names from a file's JSON alone.

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TestPaths.h"
#include "VariantFixture.h"
#include "encore/scene/SceneData.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::expectError;
using testing::loadGltf;

json& leftMappings(test::GltfBuilder& builder) {
    return builder
        .json()["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"];
}

TEST(MaterialVariantsTest, LoadsTheVariantsAndEachPrimitivesMappings) {
    auto scene = loadGltf(test::variantQuads());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->warnings.empty());
    ASSERT_EQ(scene->variants.size(), test::kVariantNames.size());
    for (std::size_t v = 0; v < test::kVariantNames.size(); ++v) {
        EXPECT_EQ(scene->variants[v], test::kVariantNames[v]);
    }
    ASSERT_EQ(scene->meshes.size(), 1u);
    const Primitive& left = scene->meshes[0].primitives[0];
    const Primitive& right = scene->meshes[0].primitives[1];
    // Materials 0 (red) .. 4 (textured) in file order, 5 the grey of the right quad.
    EXPECT_EQ(left.material.value, 0u);
    ASSERT_EQ(left.variantMaterials.size(), 4u);
    for (std::uint32_t v = 0; v < 4; ++v) {
        EXPECT_EQ(left.variantMaterials[v].variant.value, v);
        EXPECT_EQ(left.materialFor(VariantId(v)).value, v + 1);
    }
    EXPECT_EQ(left.materialFor(std::nullopt).value, 0u);
    EXPECT_TRUE(right.variantMaterials.empty());
    for (std::uint32_t v = 0; v < 4; ++v) {
        EXPECT_EQ(right.materialFor(VariantId(v)).value, 5u);  // Unmapped: its own material.
    }
}

TEST(MaterialVariantsTest, OneMappingMayNameSeveralVariantsInAnyOrder) {
    auto builder = test::variantQuads();
    leftMappings(builder) = {{{"material", 2}, {"variants", {3, 0}}},
                             {{"material", 4}, {"variants", {1}}}};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Primitive& left = scene->meshes[0].primitives[0];
    ASSERT_EQ(left.variantMaterials.size(), 3u);
    EXPECT_EQ(left.variantMaterials[0].variant.value, 0u);  // Sorted by variant.
    EXPECT_EQ(left.materialFor(VariantId(0u)).value, 2u);
    EXPECT_EQ(left.materialFor(VariantId(1u)).value, 4u);
    EXPECT_EQ(left.materialFor(VariantId(2u)).value, 0u);  // Not mapped: the default.
    EXPECT_EQ(left.materialFor(VariantId(3u)).value, 2u);
}

TEST(MaterialVariantsTest, FindsAVariantByNameThenByIndex) {
    auto scene = loadGltf(test::variantQuads());
    ASSERT_TRUE(scene.ok());
    EXPECT_EQ(findVariant(*scene, "blue paint"), VariantId(1u));
    EXPECT_EQ(findVariant(*scene, "3"), VariantId(3u));
    EXPECT_EQ(findVariant(*scene, "4"), std::nullopt);
    EXPECT_EQ(findVariant(*scene, ""), std::nullopt);
    EXPECT_EQ(findVariant(*scene, "Green"), std::nullopt);  // Names are exact.
    // A name that reads as a number wins over the index.
    const std::vector<std::string> numbered = {"1", "0"};
    EXPECT_EQ(findVariant(numbered, "1"), VariantId(0u));

    const auto missing = resolveVariant(*scene, "red");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(missing.error().message,
              "'test.gltf' has no material variant 'red' (its variants: 0 'green', 1 'blue "
              "paint', 2 'glass', 3 'textured'; give a name or an index).");
    auto plain = loadGltf(testing::triangleBuilder());
    ASSERT_TRUE(plain.ok());
    const auto none = resolveVariant(*plain, "0");
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("it uses no KHR_materials_variants"), std::string::npos)
        << none.error().message;
}

TEST(MaterialVariantsTest, BadMappingsAreErrorsNamingThePrimitive) {
    {
        auto builder = test::variantQuads();
        leftMappings(builder)[1]["material"] = 9;
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"mesh 0, primitive 0 KHR_materials_variants mapping 1 refers to material 9",
                     "6 materials"});
    }
    {
        auto builder = test::variantQuads();
        leftMappings(builder)[0]["variants"] = {7};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"mapping 0 refers to variant 7, but the asset has 4 variants"});
    }
    {
        auto builder = test::variantQuads();
        leftMappings(builder)[2]["variants"] = {0};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"mesh 0, primitive 0 KHR_materials_variants maps variant 0 more than once",
                     "materials 1 and 3"});
    }
    {
        auto builder = test::variantQuads();
        leftMappings(builder)[0].erase("variants");
        expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"mapping 0 names no variant"});
    }
    {
        auto builder = test::variantQuads();
        builder.json()["extensions"]["KHR_materials_variants"]["variants"][2] = {{"title", "x"}};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                    {"KHR_materials_variants variant 2", "'name'"});
    }
    {
        auto builder = test::variantQuads();
        builder.json()["extensions"]["KHR_materials_variants"] = {{"variants", 3}};
        expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"'variants'"});
    }
}

TEST(MaterialVariantsTest, AFileMayRequireTheExtension) {
    auto builder = test::variantQuads();
    builder.json()["extensionsRequired"] = {"KHR_materials_variants"};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_EQ(scene->variants.size(), 4u);
}

TEST(MaterialVariantsTest, ReadsTheNamesFromTheJsonAlone) {
    const auto dir = test::makeTempDir("variant-names");
    const auto builder = test::variantQuads();
    const std::vector<std::string> expected(test::kVariantNames.begin(), test::kVariantNames.end());
    for (const auto& path : {builder.writeGltf(dir, "quads"), builder.writeGlb(dir, "quads")}) {
        SCOPED_TRACE(path.string());
        auto names = readVariantNames(path);
        ASSERT_TRUE(names.ok()) << names.error().message;
        EXPECT_EQ(*names, expected);
    }
    // A .glb whose binary chunk is cut off still has its JSON read.
    const auto glb = builder.toGlb();
    const auto cut = dir / "cut.glb";
    std::ofstream(cut, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size() - 8));
    auto fromCut = readVariantNames(cut);
    ASSERT_TRUE(fromCut.ok()) << fromCut.error().message;
    EXPECT_EQ(*fromCut, expected);

    auto plain = readVariantNames(testing::triangleBuilder().writeGltf(dir, "plain"));
    ASSERT_TRUE(plain.ok());
    EXPECT_TRUE(plain->empty());
    EXPECT_FALSE(readVariantNames(dir / "missing.glb").ok());
    std::ofstream(dir / "garbage.gltf") << "{ not json";
    const auto garbage = readVariantNames(dir / "garbage.gltf");
    ASSERT_FALSE(garbage.ok());
    EXPECT_NE(garbage.error().message.find("garbage.gltf"), std::string::npos);
}

}  // namespace
}  // namespace encore::scene
