#include "gpu/FullscreenPipeline.h"

#include <vector>

namespace encore::gpu {

wgpu::RenderPipeline makeFullscreenPipeline(const wgpu::Device& device,
                                            const FullscreenPipelineDescriptor& descriptor) {
    std::vector<wgpu::ColorTargetState> colors(1 + descriptor.untouchedTargets);
    colors[0].format = descriptor.colorFormat;
    colors[0].blend = descriptor.blend ? &*descriptor.blend : nullptr;
    colors[0].writeMask = descriptor.writeMask;
    for (std::size_t i = 1; i < colors.size(); ++i) {
        colors[i].format = descriptor.colorFormat;
        colors[i].writeMask = wgpu::ColorWriteMask::None;  // The shader has no output there.
    }
    wgpu::FragmentState fragment{};
    fragment.module = descriptor.module;
    fragment.entryPoint = descriptor.fragmentEntryPoint;
    fragment.targetCount = colors.size();
    fragment.targets = colors.data();
    wgpu::DepthStencilState depth{};
    depth.format = descriptor.depthFormat;
    depth.depthWriteEnabled =
        descriptor.writesDepth ? wgpu::OptionalBool::True : wgpu::OptionalBool::False;
    depth.depthCompare = wgpu::CompareFunction::Always;

    wgpu::RenderPipelineDescriptor pipeline{};
    pipeline.label = descriptor.label;
    pipeline.layout = descriptor.layout;
    pipeline.vertex.module = descriptor.module;
    pipeline.vertex.entryPoint = descriptor.vertexEntryPoint;
    pipeline.primitive.topology = wgpu::PrimitiveTopology::TriangleList;
    pipeline.depthStencil =
        descriptor.depthFormat == wgpu::TextureFormat::Undefined ? nullptr : &depth;
    pipeline.multisample.count = descriptor.sampleCount;
    pipeline.fragment = &fragment;
    return device.CreateRenderPipeline(&pipeline);
}

void encodeFullscreenPass(const wgpu::CommandEncoder& encoder,
                          const wgpu::TextureView& target,
                          const wgpu::RenderPipeline& pipeline,
                          const wgpu::BindGroup& bindGroup,
                          wgpu::StringView label,
                          const wgpu::PassTimestampWrites* timestamps,
                          bool load) {
    wgpu::RenderPassColorAttachment color{};
    color.view = target;
    color.loadOp = load ? wgpu::LoadOp::Load : wgpu::LoadOp::Clear;
    color.storeOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = label;
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    descriptor.timestampWrites = timestamps;
    wgpu::RenderPassEncoder pass = encoder.BeginRenderPass(&descriptor);
    pass.SetPipeline(pipeline);
    pass.SetBindGroup(0, bindGroup);
    pass.Draw(3);
    pass.End();
}

}  // namespace encore::gpu
