// gpu::makeFullscreenPipeline: the triangle covers every pixel with the fragment's colour,
// blended when asked, through an explicit layout, and in passes with depth and samples.

#include <gtest/gtest.h>

#include <optional>

#include "GpuTestSupport.h"
#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Readback.h"
#include "gpu/Upload.h"

namespace encore::gpu {
namespace {

constexpr std::uint32_t kSize = 8;
constexpr wgpu::TextureFormat kFormat = wgpu::TextureFormat::RGBA8Unorm;

// The fullscreen triangle of the project's shaders (tone_mapping.wgsl, present.wgsl...), a
// constant colour and a colour from a uniform.
constexpr const char* kShader = R"(
@vertex fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let corner = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(corner * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fragmentMain() -> @location(0) vec4f { return vec4f(0.2, 0.4, 0.6, 0.5); }

@group(0) @binding(0) var<uniform> tint: vec4f;
@fragment fn tinted() -> @location(0) vec4f { return tint; }
)";

wgpu::ShaderModule shaderModule(const wgpu::Device& device) {
    wgpu::ShaderSourceWGSL wgsl;
    wgsl.code = kShader;
    wgpu::ShaderModuleDescriptor descriptor{};
    descriptor.nextInChain = &wgsl;
    return device.CreateShaderModule(&descriptor);
}

wgpu::TextureView attachment(const wgpu::Device& device,
                             wgpu::TextureFormat format,
                             std::uint32_t sampleCount) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.size = {kSize, kSize, 1};
    descriptor.format = format;
    descriptor.sampleCount = sampleCount;
    descriptor.usage = wgpu::TextureUsage::RenderAttachment;
    return device.CreateTexture(&descriptor).CreateView();
}

struct Pass {
    wgpu::BindGroup group;          // Set as group 0 when there is one.
    std::uint32_t sampleCount = 1;  // Above 1: drawn there, resolved into the target.
    bool depth = false;             // A Depth24Plus attachment cleared to 0 (nearest).
    wgpu::Color clear = {0, 0, 0, 1};
};

// Draws the pipeline's triangle over a kSize x kSize target cleared to `clear` and reads it back.
image::ImageRgba8 draw(Context& context, const wgpu::RenderPipeline& pipeline, const Pass& pass) {
    const wgpu::Device& device = context.device();
    wgpu::TextureDescriptor targetDescriptor{};
    targetDescriptor.size = {kSize, kSize, 1};
    targetDescriptor.format = kFormat;
    targetDescriptor.usage = wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc;
    const wgpu::Texture target = device.CreateTexture(&targetDescriptor);
    wgpu::RenderPassColorAttachment color{};
    color.view = target.CreateView();
    if (pass.sampleCount > 1) {
        color.resolveTarget = color.view;
        color.view = attachment(device, kFormat, pass.sampleCount);
    }
    color.loadOp = wgpu::LoadOp::Clear;
    color.storeOp = wgpu::StoreOp::Store;
    color.clearValue = pass.clear;
    wgpu::RenderPassDepthStencilAttachment depth{};
    if (pass.depth) {
        depth.view = attachment(device, wgpu::TextureFormat::Depth24Plus, pass.sampleCount);
    }
    depth.depthLoadOp = wgpu::LoadOp::Clear;
    depth.depthStoreOp = wgpu::StoreOp::Discard;
    depth.depthClearValue = 0.0f;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    descriptor.depthStencilAttachment = pass.depth ? &depth : nullptr;

    wgpu::CommandEncoder encoder = device.CreateCommandEncoder();
    wgpu::RenderPassEncoder renderPass = encoder.BeginRenderPass(&descriptor);
    renderPass.SetPipeline(pipeline);
    if (pass.group) {
        renderPass.SetBindGroup(0, pass.group);
    }
    renderPass.Draw(3);
    renderPass.End();
    const wgpu::CommandBuffer commands = encoder.Finish();
    context.queue().Submit(1, &commands);
    auto image = readTexture(context, target);
    EXPECT_TRUE(image.ok()) << image.error().message;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// Every pixel within one step of `expected` (8-bit rounding).
void expectEveryPixel(const image::ImageRgba8& image, const test::Rgba& expected) {
    ASSERT_EQ(image.width, kSize);
    ASSERT_EQ(image.height, kSize);
    for (std::uint32_t y = 0; y < kSize; ++y) {
        for (std::uint32_t x = 0; x < kSize; ++x) {
            const test::Rgba pixel = test::pixelAt(image, x, y);
            ASSERT_LE(test::channelDistance(pixel, expected), 1)
                << "pixel (" << x << ", " << y << ") is " << test::describe(pixel) << ", expected "
                << test::describe(expected);
        }
    }
}

TEST(FullscreenPipelineTest, CoversTheTargetWithTheFragmentColour) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::RenderPipeline pipeline =
        makeFullscreenPipeline(context->device(), {.label = "constant colour",
                                                   .module = shaderModule(context->device()),
                                                   .colorFormat = kFormat});
    ASSERT_TRUE(context->checkNoErrors("Making a fullscreen pipeline").ok());
    expectEveryPixel(draw(*context, pipeline, {}), {51, 102, 153, 128});
    EXPECT_TRUE(context->checkNoErrors("Drawing a fullscreen triangle").ok());
}

// Source-over blending of (0.2, 0.4, 0.6) at alpha 0.5 over opaque white.
TEST(FullscreenPipelineTest, BlendsWithTheTargetWhenGivenABlendState) {
    ENCORE_REQUIRE_VULKAN(context);
    wgpu::BlendState blend{};
    blend.color = {wgpu::BlendOperation::Add, wgpu::BlendFactor::SrcAlpha,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    blend.alpha = {wgpu::BlendOperation::Add, wgpu::BlendFactor::One,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    const wgpu::RenderPipeline pipeline =
        makeFullscreenPipeline(context->device(), {.label = "blended",
                                                   .module = shaderModule(context->device()),
                                                   .colorFormat = kFormat,
                                                   .blend = blend});
    ASSERT_TRUE(context->checkNoErrors("Making a blending fullscreen pipeline").ok());
    Pass overWhite;
    overWhite.clear = {1, 1, 1, 1};
    // 0.5 * source + 0.5 * 1 per colour channel; alpha 0.5 + 0.5 * 1.
    expectEveryPixel(draw(*context, pipeline, overWhite), {153, 179, 204, 255});
    EXPECT_TRUE(context->checkNoErrors("Drawing a blended fullscreen triangle").ok());
}

// Another fragment entry point, reading a uniform through a layout of the layout helpers.
TEST(FullscreenPipelineTest, DrawsANamedEntryPointThroughAnExplicitLayout) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::Device& device = context->device();
    const wgpu::BindGroupLayout layout = makeBindGroupLayout(
        device, {LayoutEntry::uniform(0, wgpu::ShaderStage::Fragment, 16)}, "tint");
    const wgpu::RenderPipeline pipeline =
        makeFullscreenPipeline(device, {.label = "tinted",
                                        .module = shaderModule(device),
                                        .fragmentEntryPoint = "tinted",
                                        .layout = makePipelineLayout(device, {layout}),
                                        .colorFormat = kFormat});
    const float green[4] = {0.0f, 1.0f, 0.0f, 1.0f};
    const wgpu::Buffer tint =
        createBufferFrom<float>(device, wgpu::BufferUsage::Uniform, green, "tint");
    Pass pass;
    pass.group = makeBindGroup(device, layout, {{0, tint}}, "tint");
    ASSERT_TRUE(context->checkNoErrors("Making a tinted fullscreen pipeline").ok());
    expectEveryPixel(draw(*context, pipeline, pass), {0, 255, 0, 255});
    EXPECT_TRUE(context->checkNoErrors("Drawing a tinted fullscreen triangle").ok());
}

// With a depth format the triangle passes any depth test (here against a depth buffer cleared
// to the nearest depth) and fits a multisampled pass.
TEST(FullscreenPipelineTest, IgnoresDepthAndFitsMultisampledPasses) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::RenderPipeline pipeline =
        makeFullscreenPipeline(context->device(), {.label = "behind the depth",
                                                   .module = shaderModule(context->device()),
                                                   .colorFormat = kFormat,
                                                   .depthFormat = wgpu::TextureFormat::Depth24Plus,
                                                   .sampleCount = 4});
    ASSERT_TRUE(context->checkNoErrors("Making a multisampled fullscreen pipeline").ok());
    Pass pass;
    pass.sampleCount = 4;
    pass.depth = true;
    expectEveryPixel(draw(*context, pipeline, pass), {51, 102, 153, 128});
    EXPECT_TRUE(context->checkNoErrors("Drawing a multisampled fullscreen triangle").ok());
}

}  // namespace
}  // namespace encore::gpu
