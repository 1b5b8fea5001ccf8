#pragma once

// What the visibility strategy's tests share: the picture bound of issue 28 against
// gpu-culling-bundles, and the generated scenes they render.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "RenderTestSupport.h"
#include "gpu/Readback.h"
#include "image/ImageCompare.h"
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

}  // namespace encore::test
