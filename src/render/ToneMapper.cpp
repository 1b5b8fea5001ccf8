#include "encore/render/ToneMapper.h"

#include <cmath>

#include "encore/gpu/Upload.h"

namespace encore::render {

namespace {

// struct ToneMapping of tone_mapping.wgsl, byte for byte.
struct ToneMappingUniform {
    float exposure;
    std::uint32_t toneMapping;
    std::uint32_t background;
    std::uint32_t padding;
    float backgroundColor[4];
};
static_assert(sizeof(ToneMappingUniform) == 32);

}  // namespace

Result<ToneMapper> ToneMapper::create(const wgpu::Device& device, const wgpu::Queue& queue,
                                      shaders::ShaderLibrary& shaders, const RenderTarget& target,
                                      const ToneMappingOptions& options) {
    auto module = shaders.module("tone_mapping.wgsl");
    if (!module) {
        return module.error();
    }
    ToneMapper mapper;
    mapper.mQueue = queue;

    wgpu::BindGroupLayoutEntry entries[2]{};
    entries[0].binding = 0;
    entries[0].visibility = wgpu::ShaderStage::Fragment;
    entries[0].buffer.type = wgpu::BufferBindingType::Uniform;
    entries[0].buffer.minBindingSize = sizeof(ToneMappingUniform);
    entries[1].binding = 1;
    entries[1].visibility = wgpu::ShaderStage::Fragment;
    // Read with textureLoad only, so the HDR format need not be filterable.
    entries[1].texture.sampleType = wgpu::TextureSampleType::UnfilterableFloat;
    entries[1].texture.viewDimension = wgpu::TextureViewDimension::e2D;
    wgpu::BindGroupLayoutDescriptor layoutDescriptor{};
    layoutDescriptor.label = "tone mapping";
    layoutDescriptor.entryCount = 2;
    layoutDescriptor.entries = entries;
    wgpu::BindGroupLayout layout = device.CreateBindGroupLayout(&layoutDescriptor);
    wgpu::PipelineLayoutDescriptor pipelineLayout{};
    pipelineLayout.bindGroupLayoutCount = 1;
    pipelineLayout.bindGroupLayouts = &layout;

    wgpu::ColorTargetState color{};
    color.format = RenderTarget::kColorFormat;
    wgpu::FragmentState fragment{};
    fragment.module = *module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &color;
    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "tone mapping";
    descriptor.layout = device.CreatePipelineLayout(&pipelineLayout);
    descriptor.vertex.module = *module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.fragment = &fragment;
    mapper.mPipeline = device.CreateRenderPipeline(&descriptor);

    mapper.mUniform =
        gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                          sizeof(ToneMappingUniform), "tone mapping");
    mapper.mLayout = layout;
    mapper.bindTarget(device, target);
    mapper.setOptions(options);
    return mapper;
}

void ToneMapper::bindTarget(const wgpu::Device& device, const RenderTarget& target) {
    wgpu::BindGroupEntry bindings[2]{};
    bindings[0].binding = 0;
    bindings[0].buffer = mUniform;
    bindings[0].size = sizeof(ToneMappingUniform);
    bindings[1].binding = 1;
    bindings[1].textureView = target.sceneView();
    wgpu::BindGroupDescriptor bindGroup{};
    bindGroup.label = "tone mapping";
    bindGroup.layout = mLayout;
    bindGroup.entryCount = 2;
    bindGroup.entries = bindings;
    mBindGroup = device.CreateBindGroup(&bindGroup);
}

void ToneMapper::setOptions(const ToneMappingOptions& options) {
    mOptions = options;
    ToneMappingUniform uniform{};
    uniform.exposure = options.exposure;
    uniform.toneMapping = static_cast<std::uint32_t>(options.toneMapping);
    uniform.background = static_cast<std::uint32_t>(options.background);
    for (int i = 0; i < 3; ++i) {
        uniform.backgroundColor[i] = options.backgroundColor[i];
    }
    uniform.backgroundColor[3] = 1.0f;
    mQueue.WriteBuffer(mUniform, 0, &uniform, sizeof(uniform));
}

void ToneMapper::encode(const wgpu::CommandEncoder& commands,
                        const RenderTarget& target,
                        const wgpu::PassTimestampWrites* timestamps) const {
    wgpu::RenderPassColorAttachment color{};
    color.view = target.outputView();
    color.loadOp = wgpu::LoadOp::Clear;
    color.storeOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "encore tone mapping";
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    descriptor.timestampWrites = timestamps;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, mBindGroup);
    pass.Draw(3);
    pass.End();
}

Result<EnvironmentBackground> EnvironmentBackground::create(
    const wgpu::Device& device, shaders::ShaderLibrary& shaders,
    const wgpu::BindGroupLayout& frameLayout, wgpu::TextureFormat colorFormat,
    wgpu::TextureFormat depthFormat, std::uint32_t sampleCount) {
    auto module = shaders.module("sky.wgsl");
    if (!module) {
        return module.error();
    }
    wgpu::PipelineLayoutDescriptor pipelineLayout{};
    pipelineLayout.bindGroupLayoutCount = 1;
    pipelineLayout.bindGroupLayouts = &frameLayout;
    wgpu::ColorTargetState color{};
    color.format = colorFormat;
    wgpu::FragmentState fragment{};
    fragment.module = *module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &color;
    wgpu::DepthStencilState depth{};
    depth.format = depthFormat;
    depth.depthWriteEnabled = wgpu::OptionalBool::False;
    depth.depthCompare = wgpu::CompareFunction::Always;
    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "environment background";
    descriptor.layout = device.CreatePipelineLayout(&pipelineLayout);
    descriptor.vertex.module = *module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.fragment = &fragment;
    descriptor.depthStencil = &depth;
    descriptor.multisample.count = sampleCount;
    EnvironmentBackground background;
    background.mPipeline = device.CreateRenderPipeline(&descriptor);
    return background;
}

void EnvironmentBackground::draw(const wgpu::RenderPassEncoder& pass,
                                 const wgpu::BindGroup& frame) const {
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, frame);
    pass.Draw(3);
}

}  // namespace encore::render
