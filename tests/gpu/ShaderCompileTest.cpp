// Every mesh shader variant and every other embedded shader compiles on the device: WGSL errors
// surface here, named by variant, rather than as a failing pipeline in some later test.

#include <gtest/gtest.h>

#include "GpuTestSupport.h"
#include "encore/shaders/ShaderLibrary.h"

namespace encore::shaders {
namespace {

TEST(ShaderCompileTest, EveryMeshVariantCompiles) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    std::size_t compiled = 0;
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
            ++compiled;
        }
    }
    EXPECT_EQ(compiled, 3u * 128u);
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

TEST(ShaderCompileTest, PassShadersCompile) {
    ENCORE_REQUIRE_VULKAN(context);
    ShaderLibrary library(context->device());
    for (const char* file : {"tone_mapping.wgsl", "sky.wgsl", "culling.wgsl", "mipmap.wgsl"}) {
        auto module = library.module(file);
        ASSERT_TRUE(module.ok()) << module.error().message;
        auto errors = context->checkNoErrors(std::string("compiling ") + file);
        EXPECT_TRUE(errors.ok()) << errors.error().message;
    }
}

}  // namespace
}  // namespace encore::shaders
