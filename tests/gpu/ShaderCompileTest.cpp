// Every mesh shader variant and every other embedded shader compiles on the device: WGSL errors
// surface here, named by variant, rather than as a failing pipeline in some later test.

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "GpuTestSupport.h"
#include "shaders/EmbeddedFiles.h"
#include "shaders/ShaderLibrary.h"

namespace encore::shaders {
namespace {

// The names a file tests with #if/#ifdef/#ifndef, and the files it #includes.
std::set<std::string> matches(std::string_view text, const std::regex& pattern) {
    std::set<std::string> found;
    const std::string source(text);
    for (auto it = std::sregex_iterator(source.begin(), source.end(), pattern);
         it != std::sregex_iterator(); ++it) {
        found.insert((*it)[1].str());
    }
    return found;
}

bool hasEntryPoint(std::string_view text) {
    return text.find("@compute") != std::string_view::npos ||
           text.find("@vertex") != std::string_view::npos ||
           text.find("@fragment") != std::string_view::npos;
}

TEST(ShaderCompileTest, EveryMeshVariantCompiles) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    for (InstanceSource source : {InstanceSource::NodeUniform, InstanceSource::InstanceStorage,
                                  InstanceSource::VisibleList}) {
        for (std::uint32_t bits = 0; bits < 128; ++bits) {
            ShaderVariantKey key;
            key.instanceSource = source;
            key.materials = bits & 1;
            key.hasTexcoord = bits & 2;
            key.hasColor = bits & 4;
            key.alphaMask = bits & 8;
            key.hasTexcoord1 = bits & 16;
            key.hasTangent = bits & 32;
            key.materialTextures = bits & 64;
            auto module = library.meshModule(key);
            ASSERT_TRUE(module.ok()) << module.error().message;
            auto errors = context->checkNoErrors("compiling mesh.wgsl " + key.describe());
            ASSERT_TRUE(errors.ok()) << errors.error().message;
        }
    }
}

// The material specialisations (MATERIAL_EXTENSIONS, SAMPLER_PALETTE) with and without
// textures and tangents, as MaterialDrawGroups picks them.
TEST(ShaderCompileTest, MaterialSpecialisationsCompile) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    for (std::uint32_t bits = 0; bits < 16; ++bits) {
        ShaderVariantKey key;
        key.instanceSource = InstanceSource::VisibleList;
        key.materials = true;
        key.hasTexcoord = true;
        key.materialExtensions = bits & 1;
        key.samplerPalette = bits & 2;
        key.materialTextures = bits & 4;
        key.hasTangent = bits & 8;
        auto module = library.meshModule(key);
        ASSERT_TRUE(module.ok()) << module.error().message;
        auto errors = context->checkNoErrors("compiling mesh.wgsl " + key.describe());
        ASSERT_TRUE(errors.ok()) << errors.error().message;
    }
}

// SKINNED, SKINNED_8 and MORPHED with every instance source, with and without materials (the
// animation group moves from 3 to 2) and tangents (morphed tangents).
TEST(ShaderCompileTest, AnimatedMeshVariantsCompile) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    for (InstanceSource source : {InstanceSource::NodeUniform, InstanceSource::InstanceStorage,
                                  InstanceSource::VisibleList}) {
        for (std::uint32_t bits = 1; bits < 32; ++bits) {
            ShaderVariantKey key;
            key.instanceSource = source;
            key.skinned = bits & 1;
            key.skinned8 = (bits & 2) && key.skinned;
            key.morphed = bits & 4;
            key.materials = bits & 8;
            key.hasTangent = bits & 16;
            if (!key.animated()) {
                continue;
            }
            auto module = library.meshModule(key);
            ASSERT_TRUE(module.ok()) << module.error().message;
            auto errors = context->checkNoErrors("compiling mesh.wgsl " + key.describe());
            ASSERT_TRUE(errors.ok()) << errors.error().message;
        }
    }
}

// Every embedded file with an entry point compiles on its own, without flags and with each flag
// it tests (mesh.wgsl's combinations are the tests above); every other file is a part that one
// of them includes, so a new file cannot go uncompiled.
TEST(ShaderCompileTest, EveryEmbeddedShaderCompiles) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    const std::regex flagPattern(R"(#(?:if|ifdef|ifndef|elif)\s+!?\s*([A-Z_0-9]+))");
    const std::regex includePattern(R"re(#include\s+"([^"]+)")re");
    std::set<std::string> included;
    std::set<std::string> parts;
    std::size_t entryFiles = 0;
    for (const EmbeddedFile& file : wgslFiles()) {
        const std::string name(file.name);
        for (const auto& part : matches(file.contents, includePattern)) {
            included.insert(part);
        }
        if (!hasEntryPoint(file.contents)) {
            parts.insert(name);
            continue;
        }
        ++entryFiles;
        std::vector<std::set<std::string, std::less<>>> flagSets = {{}};
        if (name != "mesh.wgsl") {
            for (const auto& flag : matches(file.contents, flagPattern)) {
                flagSets.push_back({flag});
            }
        }
        for (const auto& flags : flagSets) {
            std::string label = "compiling " + name;
            for (const auto& flag : flags) {
                label += " " + flag;
            }
            auto module = library.module(name, flags);
            ASSERT_TRUE(module.ok()) << label << ": " << module.error().message;
            auto errors = context->checkNoErrors(label);
            EXPECT_TRUE(errors.ok()) << errors.error().message;
        }
    }
    // src/shaders holds both kinds: files with entry points (mesh, culling, the environment
    // passes, ...) and parts (brdf, frame, material, ...).
    EXPECT_GE(entryFiles, 10u);
    EXPECT_FALSE(parts.empty());
    for (const auto& part : parts) {
        EXPECT_TRUE(included.count(part)) << part << " has no entry point and no file includes it";
    }
}

}  // namespace
}  // namespace encore::shaders
