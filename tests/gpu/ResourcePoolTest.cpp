// gpu::ResourcePool (buffers and textures kept from one scene to the next) and
// gpu::CreationCounts (what a thread created): a kept resource is handed out only for the same
// description, what cannot be written again is not kept, the pool stays under its limit, and a
// scene drawn into kept textures and buffers has the pixels of one drawn into new ones.

#include <gtest/gtest.h>

#include <thread>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TextureFixtures.h"
#include "encore/render/Renderer.h"
#include "gpu/CreationCounts.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/renderer/RendererCore.h"

namespace encore::gpu {
namespace {

constexpr wgpu::BufferUsage kWritable = wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst;

wgpu::TextureDescriptor textureDescriptor(std::uint32_t size, std::uint32_t mips) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.size = {size, size, 1};
    descriptor.format = wgpu::TextureFormat::RGBA8Unorm;
    descriptor.mipLevelCount = mips;
    descriptor.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst;
    return descriptor;
}

TEST(ResourcePoolTest, TexturesComeBackForTheSameDescriptionOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    ResourcePool pool(context->device());
    wgpu::Texture first = pool.texture(textureDescriptor(16, 5));
    WGPUTexture handle = first.Get();
    pool.giveBack(std::move(first));
    EXPECT_GT(pool.keptBytes(), 0u);

    // Another mip count, another size: new textures; the kept one stays kept.
    EXPECT_NE(pool.texture(textureDescriptor(16, 1)).Get(), handle);
    EXPECT_NE(pool.texture(textureDescriptor(8, 4)).Get(), handle);
    const wgpu::Texture again = pool.texture(textureDescriptor(16, 5));
    EXPECT_EQ(again.Get(), handle);
    EXPECT_EQ(pool.reused(), 1u);
    EXPECT_EQ(pool.created(), 3u);
    EXPECT_EQ(pool.keptBytes(), 0u);
    EXPECT_TRUE(context->checkNoErrors("pooled textures").ok());
}

TEST(ResourcePoolTest, BuffersComeBackForTheSameSizeAndUsageOnly) {
    ENCORE_REQUIRE_VULKAN(context);
    ResourcePool pool(context->device());
    wgpu::Buffer buffer = pool.buffer(kWritable, 100, "pooled");
    EXPECT_EQ(buffer.GetSize(), 100u);
    WGPUBuffer handle = buffer.Get();
    pool.giveBack(std::move(buffer));

    // Shaders read a buffer's size (arrayLength): a larger kept one is no substitute.
    EXPECT_NE(pool.buffer(kWritable, 104, "larger").Get(), handle);
    EXPECT_NE(pool.buffer(kWritable | wgpu::BufferUsage::CopySrc, 100, "other usage").Get(),
              handle);
    EXPECT_EQ(pool.buffer(kWritable, 99, "rounded up to 100").Get(), handle);

    // What cannot be written again is released, not kept.
    pool.giveBack(createBuffer(context->device(), wgpu::BufferUsage::Storage, 64, "read-only"));
    EXPECT_EQ(pool.keptBytes(), 0u);
    EXPECT_TRUE(context->checkNoErrors("pooled buffers").ok());
}

TEST(ResourcePoolTest, KeepsAtMostItsLimitGivingUpTheLongestUnused) {
    ENCORE_REQUIRE_VULKAN(context);
    ResourcePool pool(context->device(), 1000);
    wgpu::Buffer older = pool.buffer(kWritable, 600, "older");
    wgpu::Buffer newer = pool.buffer(kWritable, 512, "newer");
    WGPUBuffer newerHandle = newer.Get();
    pool.giveBack(std::move(older));
    pool.giveBack(std::move(newer));
    EXPECT_EQ(pool.keptBytes(), 512u);
    EXPECT_EQ(pool.buffer(kWritable, 512, "newer again").Get(), newerHandle);
    pool.buffer(kWritable, 600, "older again");
    EXPECT_EQ(pool.created(), 3u);  // The older one was given up.
    pool.giveBack(pool.buffer(kWritable, 2000, "over the limit"));
    EXPECT_EQ(pool.keptBytes(), 0u);
}

TEST(ResourcePoolTest, CreationCountsAreTheCallingThreads) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::Device& device = context->device();
    const CreationCounts before = threadCreationCounts();
    createBuffer(device, kWritable, 256, "plain");
    createBufferWithData(device, kWritable, std::vector<std::uint8_t>(40, 7), "mapped at creation");
    const wgpu::TextureDescriptor texture = textureDescriptor(4, 1);
    device.CreateTexture(&texture);
    const CreationCounts created = threadCreationCounts() - before;
    EXPECT_EQ(created.buffers, 2u);
    EXPECT_EQ(created.textures, 1u);
    EXPECT_EQ(created.objects(), 3u);
    EXPECT_EQ(created.bytesMapped, 40u);

    // Another thread's creations are its own.
    std::thread other([&] { createBuffer(device, kWritable, 256, "elsewhere"); });
    other.join();
    EXPECT_EQ((threadCreationCounts() - before).objects(), 3u);

    // A pool's reuse creates nothing.
    ResourcePool pool(device);
    pool.giveBack(pool.buffer(kWritable, 64, "kept"));
    const CreationCounts beforeReuse = threadCreationCounts();
    pool.buffer(kWritable, 64, "reused");
    EXPECT_EQ((threadCreationCounts() - beforeReuse).objects(), 0u);
    EXPECT_TRUE(context->checkNoErrors("creation counts").ok());
}

// A textured quad filling the view, its 4x4 texture of one colour.
scene::SceneData texturedQuad(std::array<std::uint8_t, 4> rgba) {
    test::GltfBuilder builder;
    const auto png = test::encodePngBytes(test::solidImage(rgba, 4, 4));
    const std::uint32_t image = test::addEmbeddedImage(builder, png, "image/png");
    builder.json()["textures"].push_back({{"source", image}});
    const auto material = builder.addMaterial({.baseColorTexture = 0});
    test::GltfBuilder::PrimitiveDesc primitive;
    const glm::vec3 facing(0.0f, 0.0f, 1.0f);
    primitive.attributes["POSITION"] =
        builder.addPositions({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}});
    primitive.attributes["NORMAL"] = builder.addNormals({facing, facing, facing, facing});
    primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    primitive.material = material;
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "quad.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// Draws `scene` with `renderer`; `created` receives what preparing it created.
image::ImageRgba8 draw(render::Renderer& renderer,
                       const scene::SceneData& scene,
                       CreationCounts* created = nullptr) {
    const CreationCounts before = threadCreationCounts();
    auto prepared = renderer.prepare(scene, render::StrategyKind::Materials);
    EXPECT_TRUE(prepared.ok()) << prepared.error().message;
    if (created) {
        *created = threadCreationCounts() - before;
    }
    renderer.renderFrame(test::frontCamera());
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

TEST(ResourcePoolTest, SceneInKeptResourcesDrawsTheSamePixelsAsInNewOnes) {
    ENCORE_REQUIRE_VULKAN(context);
    const scene::SceneData red = texturedQuad({255, 0, 0, 255});
    const scene::SceneData green = texturedQuad({0, 255, 0, 255});

    ResourcePool pool(context->device());  // Before the renderer: it outlives its scenes.
    auto pooled = render::Renderer::create(*context, test::pixelTestOptions(32, 32));
    ASSERT_TRUE(pooled.ok()) << pooled.error().message;
    internals(*pooled).setResourcePool(&pool);
    draw(*pooled, red);
    // Green goes into red's texture, geometry, instance and material buffers.
    CreationCounts created;
    const image::ImageRgba8 reused = draw(*pooled, green, &created);
    EXPECT_EQ(created.objects(), 0u);
    EXPECT_EQ(created.bytesMapped, 0u);
    EXPECT_GE(pool.reused(), 5u);  // Texture, default white, geometry, instances, uniforms.

    auto fresh = render::Renderer::create(*context, test::pixelTestOptions(32, 32));
    ASSERT_TRUE(fresh.ok()) << fresh.error().message;
    const image::ImageRgba8 drawnFresh = draw(*fresh, green);
    ASSERT_EQ(reused.pixels.size(), drawnFresh.pixels.size());
    EXPECT_EQ(reused.pixels, drawnFresh.pixels);
    EXPECT_LE(test::channelDistance(test::pixelAt(reused, 16, 16), {0, 255, 0, 255}), 1)
        << test::describe(test::pixelAt(reused, 16, 16));
    EXPECT_TRUE(context->checkNoErrors("kept resources").ok());
}

}  // namespace
}  // namespace encore::gpu
