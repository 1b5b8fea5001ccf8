#pragma once

// What the visibility strategy's tests share: the picture bound of issue 28 against
// gpu-culling-bundles, and the generated and in-code scenes they render.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "GltfBuilder.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "image/ImageCompare.h"
#include "render/visibility/VisibilityStrategy.h"
#include "scene/SceneGenerator.h"

namespace encore::test {

// What the issue asks of the visibility strategy's pictures against gpu-culling-bundles: SSIM
// >= 0.99 (`minSsim`) and at most 0.5% of pixels more than 2 levels apart (`maxDiffering` of
// them).
inline void expectVisibilityClose(const image::ImageRgba8& expected,
                                  const image::ImageRgba8& image,
                                  double maxDiffering = 0.005,
                                  double minSsim = 0.99) {
    ASSERT_EQ(expected.width, image.width);
    const auto ssim = image::ssimLuminance(expected, image);
    ASSERT_TRUE(ssim.ok());
    EXPECT_GE(*ssim, minSsim);
    const std::size_t pixels = std::size_t(image.width) * image.height;
    EXPECT_LE(double(differingPixels(expected, image, 2)), double(pixels) * maxDiffering);
}

// The u32 at `offset` of `buffer` (CopySrc): the visibility strategy's counters.
inline std::uint32_t readWord(gpu::Context& context,
                              const wgpu::Buffer& buffer,
                              std::uint64_t offset) {
    auto bytes = gpu::readBuffer(context, buffer, offset, 4);
    EXPECT_TRUE(bytes.ok());
    std::uint32_t word = 0;
    if (bytes.ok()) {
        std::memcpy(&word, bytes->data(), 4);
    }
    return word;
}

// A generated scene of `objects` objects in `layout`: six meshes, four materials, textured.
inline scene::SceneData generatedVisibilityScene(scene::SceneLayout layout, std::uint32_t objects) {
    scene::GeneratorOptions options;
    options.layout = layout;
    options.objectCount = objects;
    options.meshCount = 6;
    options.materialCount = 4;
    options.textures = true;
    return generatedScene(options);
}

// A mesh of `triangles` (positions, three per triangle) with one material per triangle, so that
// a pixel's colour says which triangle covered it; those from `firstWithMode` on have
// `alphaMode`, the others are opaque.
inline scene::SceneData triangles(const std::vector<std::array<glm::vec3, 3>>& list,
                                  const std::string& alphaMode = "OPAQUE",
                                  std::size_t firstWithMode = 0) {
    test::GltfBuilder builder;
    std::vector<test::GltfBuilder::PrimitiveDesc> primitives;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const auto positions = builder.addPositions({list[i][0], list[i][1], list[i][2]});
        const float hue = float(i + 1) / float(list.size() + 1);
        const auto material =
            builder.addMaterial({.baseColor = {hue, 1.0f - hue, std::fmod(hue * 7.0f, 1.0f), 1.0f},
                                 .alphaMode = i >= firstWithMode ? alphaMode : "OPAQUE",
                                 .doubleSided = true});
        primitives.push_back({.attributes = {{"POSITION", positions}}, .material = material});
    }
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitives)})});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "triangles.glb");
    EXPECT_TRUE(scene.ok());
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// The size the visibility tests render at.
constexpr std::uint32_t kVisibilityWidth = 128;
constexpr std::uint32_t kVisibilityHeight = 96;

// A frame of `scene` drawn by `kind` at kVisibilityWidth x kVisibilityHeight (occlusion on, no
// levels of detail), with the compute raster's limits given.
inline image::ImageRgba8 render(
    gpu::Context& context,
    const scene::SceneData& scene,
    render::StrategyKind kind,
    const render::Camera& camera,
    render::DebugChannel channel,
    float computePixels = render::VisibilityStrategy::kDefaultComputePixels,
    float workgroupPixels = render::VisibilityStrategy::kMaxWorkgroupPixels,
    std::uint32_t samples = 1) {
    render::RendererOptions options =
        pixelTestOptions(kVisibilityWidth, kVisibilityHeight, samples, channel);
    auto renderer = render::Renderer::create(context, options);
    EXPECT_TRUE(renderer.ok());
    if (!renderer.ok()) {
        return {};
    }
    render::CullingOptions culling{.occlusion = true, .levelsOfDetail = false};
    culling.computeRasterPixels = computePixels;
    culling.workgroupRasterPixels = workgroupPixels;
    renderer->setCullingOptions(culling);
    auto prepared = renderer->prepare(scene, kind);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    renderer->renderFrame(camera);
    auto image = renderer->readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

}  // namespace encore::test
