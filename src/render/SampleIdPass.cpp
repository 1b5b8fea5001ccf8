#include "render/SampleIdPass.h"

#include "encore/render/RenderTarget.h"
#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"

namespace encore::render {

Result<SampleIdPass> SampleIdPass::create(const wgpu::Device& device,
                                          shaders::ShaderLibrary& shaders,
                                          IdChannels channels) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("sample_ids.wgsl"));
    SampleIdPass pass;
    pass.mLayout = gpu::makeBindGroupLayout(
        device,
        {gpu::LayoutEntry::texture(0, wgpu::ShaderStage::Fragment,
                                   wgpu::TextureSampleType::UnfilterableFloat,
                                   wgpu::TextureViewDimension::e2D, true)},
        "sample ids");
    // The id times the resolved coverage, as the resolve leaves ids where all samples agree.
    wgpu::BlendComponent byCoverage{};
    byCoverage.srcFactor = wgpu::BlendFactor::DstAlpha;
    byCoverage.dstFactor = wgpu::BlendFactor::Zero;
    wgpu::BlendComponent alpha{};  // Masked out: written as it is.
    const bool redGreen = channels == IdChannels::RedGreen;
    pass.mPipeline = gpu::makeFullscreenPipeline(
        device, {.label = "sample ids",
                 .module = module,
                 .fragmentEntryPoint = redGreen ? "channelIds" : "passTargetIds",
                 .layout = gpu::makePipelineLayout(device, {pass.mLayout}),
                 .colorFormat = RenderTarget::kHdrFormat,
                 .blend = wgpu::BlendState{byCoverage, alpha},
                 .writeMask = redGreen ? wgpu::ColorWriteMask::Red | wgpu::ColorWriteMask::Green
                                       : wgpu::ColorWriteMask::Green | wgpu::ColorWriteMask::Blue});
    return pass;
}

void SampleIdPass::bindSource(const wgpu::Device& device, const wgpu::TextureView& multisampled) {
    mBindGroup = gpu::makeBindGroup(device, mLayout, {{0, multisampled}}, "sample ids");
}

void SampleIdPass::encode(const wgpu::CommandEncoder& commands,
                          const wgpu::TextureView& resolved) const {
    gpu::encodeFullscreenPass(commands, resolved, mPipeline, mBindGroup, "encore sample ids",
                              nullptr, true);
}

}  // namespace encore::render
