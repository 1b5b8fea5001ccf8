#pragma once

// Shared pieces of the GPU tests (CTest label "gpu"): one Vulkan context per test binary, and
// pixel helpers. Every GPU test fails loudly unless the adapter is Vulkan: Dawn's Null backend
// would "pass" by rendering nothing.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/StrategyKind.h"
#include "encore/scene/SceneData.h"
#include "scene/SceneGenerator.h"

namespace encore::test {

// The process-wide context, created on first use. Fails the calling test (ADD_FAILURE) and
// returns nullptr when no Vulkan adapter exists.
gpu::Context* vulkanContext();

// Use in a test body: gets the context or stops the test with a failure.
#define ENCORE_REQUIRE_VULKAN(contextVariable)                                               \
    gpu::Context* contextVariable = ::encore::test::vulkanContext();                         \
    ASSERT_NE(contextVariable, nullptr) << "GPU tests need Dawn's Vulkan backend (lavapipe " \
                                           "from Mesa >= 25 or a GPU driver)";               \
    ASSERT_EQ(contextVariable->adapterDescription().backend, wgpu::BackendType::Vulkan)

using Rgba = std::array<std::uint8_t, 4>;

Rgba pixelAt(const image::ImageRgba8& image, std::uint32_t x, std::uint32_t y);

// A strategy's name as a GoogleTest parameter name ("gpu-culling" -> "gpu_culling").
std::string strategyTestName(render::StrategyKind kind);

// Every strategy, directly and (where it is not a bundled kind itself) from bundles.
std::vector<render::StrategyChoice> everyStrategyChoice();
// Whether the strategy's frames shade materials (from `materials` on; the earlier ones draw
// their base colour unlit).
bool shadesMaterials(render::StrategyKind kind);
std::string describe(const Rgba& color);

// Largest per-channel difference.
int channelDistance(const Rgba& a, const Rgba& b);

// Fraction of pixels that differ from `background` by more than `tolerance` on some channel.
double coveredFraction(const image::ImageRgba8& image, const Rgba& background, int tolerance = 2);

// Number of pixels whose colour differs by more than `tolerance` on some channel.
std::size_t differingPixels(const image::ImageRgba8& a,
                            const image::ImageRgba8& b,
                            int tolerance = 0);

// The 8-bit sRGB encoding of a linear value in [0, 1].
std::uint8_t linearToSrgb8(double linear);

// One variant of a model listed in shared/models/index.json.
struct ModelVariant {
    std::string model;             // e.g. "Duck"
    std::string variant;           // e.g. "glTF-Draco"
    std::string path;              // absolute
    std::string testName() const;  // "Duck_glTF_Draco"
};
std::vector<ModelVariant> sharedModelVariants();

// A scene from the generator, loaded as `encore gen` output would be (a test failure, and an
// empty scene, when it cannot be).
scene::SceneData generatedScene(const scene::GeneratorOptions& options);
// A generated scene of `objects` textured objects (3 meshes, 2 materials) written as `path`, as
// `encore gen` writes it (a test failure when it cannot be).
void writeGeneratedScene(const std::filesystem::path& path,
                         std::uint32_t objects,
                         std::uint32_t seed);
// Lets GoogleTest print a variant by name instead of its bytes.
void PrintTo(const ModelVariant& variant, std::ostream* out);

}  // namespace encore::test
