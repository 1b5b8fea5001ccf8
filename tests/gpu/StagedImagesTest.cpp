// render::StagedImages: textures whose pixels the pool copied into staging buffers hold what
// Queue::WriteTexture puts in them, mip chain included, whatever the row padding; copies that
// never ran when the staging goes away neither block nor write.

#include <gtest/gtest.h>

#include <functional>
#include <thread>
#include <vector>

#include "GpuTestSupport.h"
#include "gpu/Readback.h"
#include "render/BindGroupLayouts.h"
#include "render/MaterialResources.h"
#include "render/StagedImages.h"

namespace encore::render {
namespace {

// A width x height image of a gradient that differs per channel, so that a row or column out
// of place shows.
scene::Image gradient(const std::string& name, std::uint32_t width, std::uint32_t height) {
    scene::Image image;
    image.name = name;
    image.width = width;
    image.height = height;
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            image.rgba8.insert(image.rgba8.end(), {std::uint8_t(x * 7), std::uint8_t(y * 13),
                                                   std::uint8_t(x ^ y), std::uint8_t(255 - x)});
        }
    }
    return image;
}

// A scene whose one material samples every image: as base colour (sRGB) the first, as
// metallic-roughness (linear) all of them in turn through further materials.
scene::SceneData sceneOf(std::vector<scene::Image> images) {
    scene::SceneData scene;
    scene.images = std::move(images);
    scene.samplers.emplace_back();
    for (std::uint32_t index = 0; index < scene.images.size(); ++index) {
        scene.textures.push_back({scene::ImageId{index}, scene::SamplerId{0u}});
        scene::Material material;
        material.baseColorTexture = scene::TextureRef{scene::TextureId{index}};
        material.metallicRoughnessTexture = scene::TextureRef{scene::TextureId{index}};
        scene.materials.push_back(material);
    }
    return scene;
}

TEST(StagedImagesTest, StagedTexturesHoldWhatWrittenOnesHold) {
    ENCORE_REQUIRE_VULKAN(context);
    // 37 pixels: rows of 148 bytes, padded to 256 in the staging buffer; 64: exactly 256.
    const scene::SceneData scene =
        sceneOf({gradient("odd", 37, 5), gradient("aligned", 64, 9), scene::Image{}});
    shaders::ShaderLibrary shaders(context->device());
    const BindGroupLayouts layouts = BindGroupLayouts::create(context->device());

    auto written = MaterialResources::create(context->device(), context->queue(), shaders, layouts,
                                             scene, SampledTextures::all());
    ASSERT_TRUE(written.ok()) << written.error().message;

    // The copies run on other threads, as the batch's pool runs them.
    std::vector<std::thread> threads;
    auto staged = StagedImages::stage(
        context->device(), scene, 8192,
        [&](std::function<void()> copy) { threads.emplace_back(std::move(copy)); });
    EXPECT_EQ(staged->bytes(), 256u * 5 + 256u * 9);
    auto copied =
        MaterialResources::create(context->device(), context->queue(), shaders, layouts, scene,
                                  SampledTextures::all(), 0, nullptr, staged.get());
    for (std::thread& thread : threads) {
        thread.join();
    }
    ASSERT_TRUE(copied.ok()) << copied.error().message;
    EXPECT_EQ(copied->textureCount(), written->textureCount());

    for (std::uint32_t image = 0; image < 2; ++image) {
        for (const ColorSpace space : {ColorSpace::Srgb, ColorSpace::Linear}) {
            const wgpu::Texture* expected = written->texture(scene::ImageId{image}, space);
            const wgpu::Texture* actual = copied->texture(scene::ImageId{image}, space);
            ASSERT_NE(expected, nullptr);
            ASSERT_NE(actual, nullptr);
            for (std::uint32_t level = 0; level < expected->GetMipLevelCount(); ++level) {
                auto want = gpu::readTextureLevel(*context, *expected, level);
                auto got = gpu::readTextureLevel(*context, *actual, level);
                ASSERT_TRUE(want.ok() && got.ok());
                EXPECT_TRUE(want->pixels == got->pixels)
                    << scene.images[image].name << " level " << level;
            }
        }
    }
    EXPECT_TRUE(context->checkNoErrors("staged textures").ok());
}

TEST(StagedImagesTest, CopiesNotRunWhenTheStagingGoesAwayDoNothing) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData scene = sceneOf({gradient("a", 16, 16), gradient("b", 8, 4)});
    std::vector<std::function<void()>> queued;
    auto staged =
        StagedImages::stage(context->device(), scene, 8192,
                            [&](std::function<void()> copy) { queued.push_back(std::move(copy)); });
    ASSERT_EQ(queued.size(), 2u);
    queued[0]();  // One ran, the other never started.
    staged.reset();
    queued[1]();  // Runs after the staging is gone: finds its copy claimed.
    EXPECT_TRUE(context->checkNoErrors("dropped staging").ok());
}

}  // namespace
}  // namespace encore::render
