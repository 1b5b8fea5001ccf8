#include "view/Presenter.h"

#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"

namespace encore::view {

Result<Presenter> Presenter::create(const wgpu::Device& device,
                                    shaders::ShaderLibrary& shaders,
                                    wgpu::TextureFormat surfaceFormat) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("present.wgsl"));
    Presenter presenter;
    presenter.mDevice = device;
    presenter.mLayout = gpu::makeBindGroupLayout(
        device, {gpu::LayoutEntry::texture(0, wgpu::ShaderStage::Fragment)}, "present");
    presenter.mPipeline = gpu::makeFullscreenPipeline(
        device, {.label = "present",
                 .module = module,
                 .layout = gpu::makePipelineLayout(device, {presenter.mLayout}),
                 .colorFormat = surfaceFormat});
    return presenter;
}

void Presenter::encode(const wgpu::CommandEncoder& commands,
                       const wgpu::TextureView& source,
                       const wgpu::TextureView& target) {
    if (source.Get() != mBoundSource.Get()) {
        mBindGroup = gpu::makeBindGroup(mDevice, mLayout, {{0, source}}, "present");
        mBoundSource = source;
    }
    gpu::encodeFullscreenPass(commands, target, mPipeline, mBindGroup, "encore present");
}

}  // namespace encore::view
