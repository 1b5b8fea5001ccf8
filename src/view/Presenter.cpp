#include "encore/view/Presenter.h"

namespace encore::view {

Result<Presenter> Presenter::create(const wgpu::Device& device, shaders::ShaderLibrary& shaders,
                                    wgpu::TextureFormat surfaceFormat) {
    auto module = shaders.module("present.wgsl");
    if (!module) {
        return module.error();
    }
    Presenter presenter;
    presenter.mDevice = device;
    wgpu::BindGroupLayoutEntry entry{};
    entry.binding = 0;
    entry.visibility = wgpu::ShaderStage::Fragment;
    entry.texture.sampleType = wgpu::TextureSampleType::Float;
    entry.texture.viewDimension = wgpu::TextureViewDimension::e2D;
    wgpu::BindGroupLayoutDescriptor layout{};
    layout.label = "present";
    layout.entryCount = 1;
    layout.entries = &entry;
    presenter.mLayout = device.CreateBindGroupLayout(&layout);
    wgpu::PipelineLayoutDescriptor pipelineLayout{};
    pipelineLayout.bindGroupLayoutCount = 1;
    pipelineLayout.bindGroupLayouts = &presenter.mLayout;

    wgpu::ColorTargetState color{};
    color.format = surfaceFormat;
    wgpu::FragmentState fragment{};
    fragment.module = *module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &color;
    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "present";
    descriptor.layout = device.CreatePipelineLayout(&pipelineLayout);
    descriptor.vertex.module = *module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.fragment = &fragment;
    presenter.mPipeline = device.CreateRenderPipeline(&descriptor);
    return presenter;
}

void Presenter::encode(const wgpu::CommandEncoder& commands, const wgpu::TextureView& source,
                       const wgpu::TextureView& target) {
    if (source.Get() != mBoundSource.Get()) {
        wgpu::BindGroupEntry entry{};
        entry.binding = 0;
        entry.textureView = source;
        wgpu::BindGroupDescriptor bindGroup{};
        bindGroup.label = "present";
        bindGroup.layout = mLayout;
        bindGroup.entryCount = 1;
        bindGroup.entries = &entry;
        mBindGroup = mDevice.CreateBindGroup(&bindGroup);
        mBoundSource = source;
    }
    wgpu::RenderPassColorAttachment color{};
    color.view = target;
    color.loadOp = wgpu::LoadOp::Clear;
    color.storeOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "encore present";
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, mBindGroup);
    pass.Draw(3);
    pass.End();
}

}  // namespace encore::view
