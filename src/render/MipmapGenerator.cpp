#include "render/MipmapGenerator.h"

#include <algorithm>
#include <bit>
#include <string>

#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"

namespace encore::render {

std::uint32_t fullMipLevelCount(std::uint32_t width, std::uint32_t height) {
    const std::uint32_t largest = std::max(std::max(width, height), 1u);
    return static_cast<std::uint32_t>(std::bit_width(largest));
}

Result<MipmapGenerator> MipmapGenerator::create(const wgpu::Device& device,
                                                shaders::ShaderLibrary& shaders) {
    auto module = shaders.module("mipmap.wgsl");
    if (!module) {
        return module.error().withContext("Creating the mipmap generator");
    }
    MipmapGenerator generator;
    generator.mDevice = device;
    generator.mModule = *module;

    wgpu::SamplerDescriptor sampler{};
    sampler.label = "mipmap downsample";
    sampler.addressModeU = wgpu::AddressMode::ClampToEdge;
    sampler.addressModeV = wgpu::AddressMode::ClampToEdge;
    sampler.magFilter = wgpu::FilterMode::Linear;
    sampler.minFilter = wgpu::FilterMode::Linear;
    generator.mSampler = device.CreateSampler(&sampler);

    generator.mLayout =
        gpu::makeBindGroupLayout(device,
                                 {gpu::LayoutEntry::sampler(0, wgpu::ShaderStage::Fragment),
                                  gpu::LayoutEntry::texture(1, wgpu::ShaderStage::Fragment)},
                                 "mipmap source");
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

    wgpu::TextureViewDescriptor viewDescriptor{};
    viewDescriptor.dimension = wgpu::TextureViewDimension::e2D;
    viewDescriptor.mipLevelCount = 1;
    viewDescriptor.arrayLayerCount = 1;
    viewDescriptor.baseMipLevel = 0;
    wgpu::TextureView source = texture.CreateView(&viewDescriptor);
    for (std::uint32_t level = 1; level < levels; ++level) {
        viewDescriptor.baseMipLevel = level;
        wgpu::TextureView destination = texture.CreateView(&viewDescriptor);

        const wgpu::BindGroup bindGroup =
            gpu::makeBindGroup(mDevice, mLayout, {{0, mSampler}, {1, source}});

        wgpu::RenderPassColorAttachment attachment{};
        attachment.view = destination;
        // Every texel of the level is overwritten, so its previous contents need no load.
        attachment.loadOp = wgpu::LoadOp::Clear;
        attachment.storeOp = wgpu::StoreOp::Store;
        wgpu::RenderPassDescriptor passDescriptor{};
        passDescriptor.label = "mipmap level";
        passDescriptor.colorAttachmentCount = 1;
        passDescriptor.colorAttachments = &attachment;
        passDescriptor.timestampWrites = mTimestamps ? mTimestamps->pass(mStage) : nullptr;
        wgpu::RenderPassEncoder pass = encoder.BeginRenderPass(&passDescriptor);
        pass.SetPipeline(downsample);
        pass.SetBindGroup(0, bindGroup);
        pass.Draw(3);
        pass.End();
        source = destination;
    }
    return {};
}

}  // namespace encore::render
