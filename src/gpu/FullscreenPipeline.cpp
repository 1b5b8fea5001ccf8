#include "gpu/FullscreenPipeline.h"

namespace encore::gpu {

wgpu::RenderPipeline makeFullscreenPipeline(const wgpu::Device& device,
                                            const FullscreenPipelineDescriptor& descriptor) {
    wgpu::ColorTargetState color{};
    color.format = descriptor.colorFormat;
    color.blend = descriptor.blend ? &*descriptor.blend : nullptr;
    wgpu::FragmentState fragment{};
    fragment.module = descriptor.module;
    fragment.entryPoint = descriptor.fragmentEntryPoint;
    fragment.targetCount = 1;
    fragment.targets = &color;
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

}  // namespace encore::gpu
