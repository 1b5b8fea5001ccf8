#include "MipmapGenerator.h"

#include <algorithm>
#include <bit>
#include <string>

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

    wgpu::BindGroupLayoutEntry entries[2]{};
    entries[0].binding = 0;
    entries[0].visibility = wgpu::ShaderStage::Fragment;
    entries[0].sampler.type = wgpu::SamplerBindingType::Filtering;
    entries[1].binding = 1;
    entries[1].visibility = wgpu::ShaderStage::Fragment;
    entries[1].texture.sampleType = wgpu::TextureSampleType::Float;
    entries[1].texture.viewDimension = wgpu::TextureViewDimension::e2D;
    wgpu::BindGroupLayoutDescriptor layout{};
    layout.label = "mipmap source";
    layout.entryCount = 2;
    layout.entries = entries;
    generator.mLayout = device.CreateBindGroupLayout(&layout);

    wgpu::PipelineLayoutDescriptor pipelineLayout{};
    pipelineLayout.label = "mipmap";
    pipelineLayout.bindGroupLayoutCount = 1;
    pipelineLayout.bindGroupLayouts = &generator.mLayout;
    generator.mPipelineLayout = device.CreatePipelineLayout(&pipelineLayout);
    return generator;
}

const wgpu::RenderPipeline& MipmapGenerator::pipeline(wgpu::TextureFormat format) {
    if (auto found = mPipelines.find(format); found != mPipelines.end()) {
        return found->second;
    }
    wgpu::ColorTargetState target{};
    target.format = format;
    wgpu::FragmentState fragment{};
    fragment.module = mModule;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &target;
    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "mipmap downsample";
    descriptor.layout = mPipelineLayout;
    descriptor.vertex.module = mModule;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.primitive.topology = wgpu::PrimitiveTopology::TriangleList;
    descriptor.fragment = &fragment;
    return mPipelines.emplace(format, mDevice.CreateRenderPipeline(&descriptor)).first->second;
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

        wgpu::BindGroupEntry entries[2]{};
        entries[0].binding = 0;
        entries[0].sampler = mSampler;
        entries[1].binding = 1;
        entries[1].textureView = source;
        wgpu::BindGroupDescriptor bindGroupDescriptor{};
        bindGroupDescriptor.layout = mLayout;
        bindGroupDescriptor.entryCount = 2;
        bindGroupDescriptor.entries = entries;
        wgpu::BindGroup bindGroup = mDevice.CreateBindGroup(&bindGroupDescriptor);

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
