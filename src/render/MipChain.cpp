#include "render/MipChain.h"

#include <algorithm>
#include <bit>

#include "gpu/LayoutEntry.h"

namespace encore::render {

std::uint32_t fullMipLevelCount(std::uint32_t width, std::uint32_t height) {
    const std::uint32_t largest = std::max(std::max(width, height), 1u);
    return static_cast<std::uint32_t>(std::bit_width(largest));
}

wgpu::Sampler makeLinearClampSampler(const wgpu::Device& device, const char* label) {
    wgpu::SamplerDescriptor sampler{};
    sampler.label = label;
    sampler.addressModeU = wgpu::AddressMode::ClampToEdge;
    sampler.addressModeV = wgpu::AddressMode::ClampToEdge;
    sampler.addressModeW = wgpu::AddressMode::ClampToEdge;
    sampler.magFilter = wgpu::FilterMode::Linear;
    sampler.minFilter = wgpu::FilterMode::Linear;
    sampler.mipmapFilter = wgpu::MipmapFilterMode::Linear;
    return device.CreateSampler(&sampler);
}

wgpu::BindGroupLayout makeMipSourceLayout(const wgpu::Device& device, const char* label) {
    return gpu::makeBindGroupLayout(device,
                                    {gpu::LayoutEntry::sampler(0, wgpu::ShaderStage::Fragment),
                                     gpu::LayoutEntry::texture(1, wgpu::ShaderStage::Fragment)},
                                    label);
}

std::vector<wgpu::TextureView> mipLevelViews(const wgpu::Texture& texture) {
    wgpu::TextureViewDescriptor level{};
    level.dimension = wgpu::TextureViewDimension::e2D;
    level.mipLevelCount = 1;
    level.arrayLayerCount = 1;
    std::vector<wgpu::TextureView> views;
    for (std::uint32_t i = 0; i < texture.GetMipLevelCount(); ++i) {
        level.baseMipLevel = i;
        views.push_back(texture.CreateView(&level));
    }
    return views;
}

}  // namespace encore::render
