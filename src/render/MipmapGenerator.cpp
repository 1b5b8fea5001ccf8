#include "render/MipmapGenerator.h"

#include <string>

#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"

namespace encore::render {

Result<MipmapGenerator> MipmapGenerator::create(const wgpu::Device& device,
                                                shaders::ShaderLibrary& shaders) {
    auto module = shaders.module("mipmap.wgsl");
    if (!module) {
        return module.error().withContext("Creating the mipmap generator");
    }
    MipmapGenerator generator;
    generator.mDevice = device;
    generator.mModule = *module;

    generator.mSampler = makeLinearClampSampler(device, "mipmap downsample");
    generator.mLayout = makeMipSourceLayout(device, "mipmap source");
    generator.mPipelineLayout = gpu::makePipelineLayout(device, {generator.mLayout}, "mipmap");
    return generator;
}

const wgpu::RenderPipeline& MipmapGenerator::pipeline(wgpu::TextureFormat format) {
    if (auto found = mPipelines.find(format); found != mPipelines.end()) {
        return found->second;
    }
    wgpu::RenderPipeline downsample =
        gpu::makeFullscreenPipeline(mDevice, {.label = "mipmap downsample",
                                              .module = mModule,
                                              .layout = mPipelineLayout,
                                              .colorFormat = format});
    return mPipelines.emplace(format, std::move(downsample)).first->second;
}

Result<void> MipmapGenerator::generate(const wgpu::CommandEncoder& encoder,
                                       const wgpu::Texture& texture) {
    if (texture.GetDimension() != wgpu::TextureDimension::e2D ||
        texture.GetDepthOrArrayLayers() != 1) {
        return makeError(
            ErrorCode::InvalidArgument,
            "Mipmaps are generated only for 2D textures with one layer (this one has " +
                std::to_string(texture.GetDepthOrArrayLayers()) + " layers).");
    }
    const wgpu::TextureUsage needed =
        wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::RenderAttachment;
    if ((texture.GetUsage() & needed) != needed) {
        return makeError(ErrorCode::InvalidArgument,
                         "Generating mipmaps needs a texture with TextureBinding and "
                         "RenderAttachment usage.");
    }
    const std::uint32_t levels = texture.GetMipLevelCount();
    if (levels < 2) {
        return {};
    }
    const wgpu::RenderPipeline& downsample = pipeline(texture.GetFormat());

    const std::vector<wgpu::TextureView> views = mipLevelViews(texture);
    for (std::uint32_t level = 1; level < levels; ++level) {
        const wgpu::BindGroup source =
            gpu::makeBindGroup(mDevice, mLayout, {{0, mSampler}, {1, views[level - 1]}});
        gpu::encodeFullscreenPass(encoder, views[level], downsample, source, "mipmap level",
                                  mTimestamps ? mTimestamps->pass(mStage) : nullptr);
    }
    return {};
}

}  // namespace encore::render
