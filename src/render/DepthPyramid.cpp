#include "encore/render/DepthPyramid.h"

#include <algorithm>

#include "encore/gpu/BindGroupEntries.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 8;  // depth_pyramid.wgsl's workgroup_size.

wgpu::TextureView levelView(const wgpu::Texture& texture, std::uint32_t level) {
    wgpu::TextureViewDescriptor descriptor{};
    descriptor.baseMipLevel = level;
    descriptor.mipLevelCount = 1;
    return texture.CreateView(&descriptor);
}

}  // namespace

Result<DepthPyramid> DepthPyramid::create(const wgpu::Device& device,
                                          shaders::ShaderLibrary& shaders,
                                          const wgpu::Texture& depth) {
    DepthPyramid pyramid;
    pyramid.mDepth = depth;
    const bool multisampled = depth.GetSampleCount() > 1;
    auto module = shaders.module("depth_pyramid.wgsl",
                                 multisampled ? std::set<std::string, std::less<>>{"MULTISAMPLED"}
                                              : std::set<std::string, std::less<>>{});
    if (!module) {
        return module.error();
    }
    auto computePipeline = [&](const char* entryPoint) {
        wgpu::ComputePipelineDescriptor descriptor{};
        descriptor.label = entryPoint;
        descriptor.compute.module = *module;
        descriptor.compute.entryPoint = entryPoint;
        return device.CreateComputePipeline(&descriptor);  // Layout from the entry point.
    };
    pyramid.mReduceDepth = computePipeline("reduceDepth");
    pyramid.mReduceLevel = computePipeline("reduceLevel");

    // Mip sizes round down; the shader's last texels cover what that drops.
    std::uint32_t width = std::max(depth.GetWidth() / 2, 1u);
    std::uint32_t height = std::max(depth.GetHeight() / 2, 1u);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes{{width, height}};
    while (width > 1 || height > 1) {
        width = std::max(width / 2, 1u);
        height = std::max(height / 2, 1u);
        sizes.emplace_back(width, height);
    }
    wgpu::TextureDescriptor descriptor{};
    descriptor.label = "depth pyramid";
    descriptor.size = {sizes[0].first, sizes[0].second, 1};
    descriptor.format = wgpu::TextureFormat::R32Float;
    descriptor.mipLevelCount = static_cast<std::uint32_t>(sizes.size());
    descriptor.usage = wgpu::TextureUsage::StorageBinding | wgpu::TextureUsage::TextureBinding |
                       wgpu::TextureUsage::CopySrc;  // Read back by tests.
    pyramid.mPyramid = device.CreateTexture(&descriptor);
    pyramid.mView = pyramid.mPyramid.CreateView();

    const wgpu::TextureView depthView = depth.CreateView();
    for (std::uint32_t level = 0; level < sizes.size(); ++level) {
        const wgpu::BindGroupEntry entries[] = {
            level == 0 ? gpu::textureEntry(0, depthView)
                       : gpu::textureEntry(1, levelView(pyramid.mPyramid, level - 1)),
            gpu::textureEntry(2, levelView(pyramid.mPyramid, level)),
        };
        wgpu::BindGroupDescriptor group{};
        group.label = "depth pyramid level";
        group.layout = (level == 0 ? pyramid.mReduceDepth : pyramid.mReduceLevel).GetBindGroupLayout(0);
        group.entryCount = std::size(entries);
        group.entries = entries;
        pyramid.mLevels.push_back({device.CreateBindGroup(&group), sizes[level].first,
                                   sizes[level].second});
    }
    return pyramid;
}

void DepthPyramid::encode(const wgpu::ComputePassEncoder& pass) const {
    for (std::size_t level = 0; level < mLevels.size(); ++level) {
        pass.SetPipeline(level == 0 ? mReduceDepth : mReduceLevel);
        pass.SetBindGroup(0, mLevels[level].bindGroup);
        pass.DispatchWorkgroups((mLevels[level].width + kWorkgroupSize - 1) / kWorkgroupSize,
                                (mLevels[level].height + kWorkgroupSize - 1) / kWorkgroupSize);
    }
}

}  // namespace encore::render
