#include "render/TransmissionPass.h"

#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"
#include "render/MipChain.h"

namespace encore::render {

wgpu::Texture TransmissionPass::createBackground(const wgpu::Device& device) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.label = "transmission background";
    descriptor.size = {kSize, kSize, 1};
    descriptor.format = kFormat;
    descriptor.mipLevelCount = fullMipLevelCount(kSize, kSize);
    descriptor.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::RenderAttachment;
    return device.CreateTexture(&descriptor);
}

Result<TransmissionPass> TransmissionPass::create(const wgpu::Device& device,
                                                  shaders::ShaderLibrary& shaders,
                                                  const wgpu::Texture& background) {
    // mipmap.wgsl draws one bilinear sample of a single-level source per texel: a resampling
    // copy into level 0, a 2x2 mean for each level below.
    auto module = shaders.module("mipmap.wgsl");
    if (!module) {
        return module.error().withContext("Creating the transmission pass");
    }
    TransmissionPass pass;
    pass.mDevice = device;
    pass.mBackground = background;
    pass.mSampler = makeLinearClampSampler(device, "transmission copy");
    pass.mLayout = makeMipSourceLayout(device, "transmission copy source");
    pass.mPipeline = gpu::makeFullscreenPipeline(
        device, {.label = "transmission copy",
                 .module = *module,
                 .layout = gpu::makePipelineLayout(device, {pass.mLayout}, "transmission copy"),
                 .colorFormat = kFormat});

    pass.mLevels = mipLevelViews(background);
    for (std::size_t i = 0; i + 1 < pass.mLevels.size(); ++i) {
        pass.mLevelSources.push_back(gpu::makeBindGroup(
            device, pass.mLayout, {{0, pass.mSampler}, {1, pass.mLevels[i]}}, "transmission mip"));
    }
    return pass;
}

void TransmissionPass::encodeCopy(const wgpu::CommandEncoder& commands,
                                  const wgpu::TextureView& source,
                                  gpu::GpuTimer* timer) {
    if (source.Get() != mSource) {
        // A new render target (resized): only this bind group follows it.
        mSource = source.Get();
        mSourceGroup = gpu::makeBindGroup(mDevice, mLayout, {{0, mSampler}, {1, source}},
                                          "transmission copy source");
    }
    for (std::size_t level = 0; level < mLevels.size(); ++level) {
        const char* label = level == 0 ? "transmission copy" : "transmission mips";
        gpu::encodeFullscreenPass(commands, mLevels[level], mPipeline,
                                  level == 0 ? mSourceGroup : mLevelSources[level - 1], label,
                                  timer ? timer->nextPass(label) : nullptr);
    }
    ++mCopies;
}

}  // namespace encore::render
