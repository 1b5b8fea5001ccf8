// gpu::LayoutEntry, makeBindGroupLayout, makePipelineLayout and gpu::BindingResource,
// makeBindGroup: layouts and groups of every kind of entry are valid, and a shader reads what
// each binding (its offsets included) points at.

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "GpuTestSupport.h"
#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Readback.h"
#include "gpu/Upload.h"

namespace encore::gpu {
namespace {

constexpr auto kCompute = wgpu::ShaderStage::Compute;
constexpr std::uint64_t kOffsetAlignment = 256;  // Uniform and storage: WebGPU's largest.

wgpu::ShaderModule wgslModule(const wgpu::Device& device, const char* code) {
    wgpu::ShaderSourceWGSL wgsl;
    wgsl.code = code;
    wgpu::ShaderModuleDescriptor descriptor{};
    descriptor.nextInChain = &wgsl;
    return device.CreateShaderModule(&descriptor);
}

wgpu::Texture texture1x1(const wgpu::Device& device, wgpu::TextureUsage usage) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.size = {1, 1, 1};
    descriptor.format = wgpu::TextureFormat::RGBA8Unorm;
    descriptor.usage = usage;
    return device.CreateTexture(&descriptor);
}

// One binding of every kind; the shader copies what each holds to `output` and `target`.
constexpr const char* kEveryKindShader = R"(
struct Params { value: u32, padding0: u32, padding1: u32, padding2: u32 }
@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> input: array<u32>;
@group(0) @binding(2) var<storage, read_write> output: array<u32>;
@group(0) @binding(3) var source: texture_2d<f32>;
@group(0) @binding(4) var nearest: sampler;
@group(0) @binding(5) var written: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(1) fn main() {
    output[0] = params.value;
    output[1] = input[0];
    output[2] = u32(textureSampleLevel(source, nearest, vec2f(0.5), 0.0).r * 255.0 + 0.5);
    textureStore(written, vec2i(0), vec4f(1.0, 0.0, 0.0, 1.0));
}
)";

TEST(BindGroupHelpersTest, EveryKindOfEntryBindsWhatTheShaderReads) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::Device& device = context->device();
    const wgpu::BindGroupLayout layout = makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, kCompute, 16).withDynamicOffset(),
         LayoutEntry::readOnlyStorage(1, kCompute, 4), LayoutEntry::storage(2, kCompute, 12),
         LayoutEntry::texture(3, kCompute, wgpu::TextureSampleType::UnfilterableFloat),
         LayoutEntry::sampler(4, kCompute, wgpu::SamplerBindingType::NonFiltering),
         LayoutEntry::storageTexture(5, kCompute, wgpu::TextureFormat::RGBA8Unorm)},
        "every kind");

    // The uniform's second slot and the input's second slot hold the values read: the dynamic
    // offset and the resource's offset must both reach the shader.
    std::vector<std::uint32_t> uniforms(2 * kOffsetAlignment / 4, 0);
    uniforms[0] = 7;
    uniforms[kOffsetAlignment / 4] = 42;
    std::vector<std::uint32_t> inputs = uniforms;
    inputs[0] = 8;
    inputs[kOffsetAlignment / 4] = 99;
    const wgpu::Buffer uniform = createBufferFrom<std::uint32_t>(device, wgpu::BufferUsage::Uniform,
                                                                 uniforms, "helper test uniform");
    const wgpu::Buffer input = createStorageBuffer(device, inputs, "helper test input");
    const wgpu::Buffer output = createBuffer(
        device, wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopySrc, 12, "helper test output");
    const wgpu::Texture source =
        texture1x1(device, wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst);
    const std::uint8_t texel[4] = {51, 0, 0, 255};
    wgpu::TexelCopyTextureInfo destination{};
    destination.texture = source;
    wgpu::TexelCopyBufferLayout texelLayout{};
    texelLayout.bytesPerRow = 4;
    const wgpu::Extent3D oneTexel = {1, 1, 1};
    context->queue().WriteTexture(&destination, texel, sizeof(texel), &texelLayout, &oneTexel);
    const wgpu::Texture target =
        texture1x1(device, wgpu::TextureUsage::StorageBinding | wgpu::TextureUsage::CopySrc);
    wgpu::SamplerDescriptor samplerDescriptor{};
    const wgpu::Sampler nearest = device.CreateSampler(&samplerDescriptor);

    const wgpu::BindGroup group = makeBindGroup(device, layout,
                                                {{0, uniform, 0, 16},
                                                 {1, input, kOffsetAlignment, 4},
                                                 {2, output},
                                                 {3, source.CreateView()},
                                                 {4, nearest},
                                                 {5, target.CreateView()}},
                                                "every kind");
    ASSERT_TRUE(context->checkNoErrors("Making a layout and group of every kind").ok());

    wgpu::ComputePipelineDescriptor pipelineDescriptor{};
    pipelineDescriptor.layout = makePipelineLayout(device, {layout});
    pipelineDescriptor.compute.module = wgslModule(device, kEveryKindShader);
    pipelineDescriptor.compute.entryPoint = "main";
    const wgpu::ComputePipeline pipeline = device.CreateComputePipeline(&pipelineDescriptor);
    wgpu::CommandEncoder encoder = device.CreateCommandEncoder();
    wgpu::ComputePassEncoder pass = encoder.BeginComputePass();
    pass.SetPipeline(pipeline);
    const std::uint32_t dynamicOffset = kOffsetAlignment;
    pass.SetBindGroup(0, group, 1, &dynamicOffset);
    pass.DispatchWorkgroups(1);
    pass.End();
    const wgpu::CommandBuffer commands = encoder.Finish();
    context->queue().Submit(1, &commands);

    auto bytes = readBuffer(*context, output, 0, 12);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    std::uint32_t read[3];
    std::memcpy(read, bytes->data(), sizeof(read));
    EXPECT_EQ(read[0], 42u) << "the uniform at the dynamic offset";
    EXPECT_EQ(read[1], 99u) << "the storage buffer from the resource's offset";
    EXPECT_EQ(read[2], 51u) << "the sampled texture";
    auto stored = readTexture(*context, target);
    ASSERT_TRUE(stored.ok()) << stored.error().message;
    EXPECT_EQ(test::pixelAt(*stored, 0, 0), (test::Rgba{255, 0, 0, 255}));
    EXPECT_TRUE(context->checkNoErrors("Running the every-kind shader").ok());
}

// The layout is enforced: a resource of the wrong kind, or at a binding the layout lacks, is a
// validation error.
TEST(BindGroupHelpersTest, ResourcesThatDoNotMatchTheLayoutAreValidationErrors) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::Device& device = context->device();
    const wgpu::BindGroupLayout layout =
        makeBindGroupLayout(device, {LayoutEntry::uniform(0, wgpu::ShaderStage::Fragment, 16)});
    const wgpu::Buffer uniform =
        createBuffer(device, wgpu::BufferUsage::Uniform, 16, "helper test uniform");
    makeBindGroup(device, layout, {{0, uniform}});
    ASSERT_TRUE(context->checkNoErrors("A matching group").ok());

    const wgpu::Texture texture = texture1x1(device, wgpu::TextureUsage::TextureBinding);
    makeBindGroup(device, layout, {{0, texture.CreateView()}});
    auto wrongKind = context->checkNoErrors("A texture for a uniform buffer");
    ASSERT_FALSE(wrongKind.ok());
    EXPECT_EQ(wrongKind.error().code, ErrorCode::ValidationError);

    makeBindGroup(device, layout, {{0, uniform}, {1, uniform}});
    auto extraBinding = context->checkNoErrors("A binding the layout lacks");
    ASSERT_FALSE(extraBinding.ok());
    EXPECT_EQ(extraBinding.error().code, ErrorCode::ValidationError);
}

// makePipelineLayout keeps the groups' order: group i has the i-th layout.
TEST(BindGroupHelpersTest, PipelineLayoutGroupsAreInOrder) {
    ENCORE_REQUIRE_VULKAN(context);
    const wgpu::Device& device = context->device();
    const wgpu::BindGroupLayout uniformLayout =
        makeBindGroupLayout(device, {LayoutEntry::uniform(0, kCompute)});
    const wgpu::BindGroupLayout storageLayout =
        makeBindGroupLayout(device, {LayoutEntry::storage(0, kCompute)});
    const wgpu::ShaderModule module = wgslModule(device, R"(
@group(0) @binding(0) var<uniform> value: vec4u;
@group(1) @binding(0) var<storage, read_write> result: array<u32>;
@compute @workgroup_size(1) fn main() { result[0] = value.x; }
)");
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = "main";
    // From a vector (as PipelineKey builds its groups) and from a braced list.
    const std::vector<wgpu::BindGroupLayout> inOrder = {uniformLayout, storageLayout};
    descriptor.layout = makePipelineLayout(device, inOrder, "in order");
    device.CreateComputePipeline(&descriptor);
    ASSERT_TRUE(context->checkNoErrors("A pipeline layout in the shader's order").ok());

    descriptor.layout = makePipelineLayout(device, {storageLayout, uniformLayout}, "swapped");
    device.CreateComputePipeline(&descriptor);
    auto swapped = context->checkNoErrors("A pipeline layout with its groups swapped");
    ASSERT_FALSE(swapped.ok());
    EXPECT_EQ(swapped.error().code, ErrorCode::ValidationError);
}

}  // namespace
}  // namespace encore::gpu
