#include "render/culling/DepthPyramid.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "gpu/BindingResource.h"
#include "gpu/Upload.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kTile = 16;              // depth_pyramid.wgsl's workgroup tile.
constexpr std::uint32_t kLevelsPerDispatch = 4;  // Its storage bindings (level0..level3).
constexpr std::uint64_t kUniformStride = 256;    // minUniformBufferOffsetAlignment's default.
// Two dispatches. Level 7's texels cover 256 pixels a side: a box larger than that (near the
// camera, and then usually visible) reads a few more texels there rather than costing a third
// dispatch on the CPU every frame.
constexpr std::uint32_t kMaxLevels = 2 * kLevelsPerDispatch;

// depth_pyramid.wgsl's Reduction.
struct ReductionUniform {
    std::uint32_t depthSize[2];
    std::uint32_t firstLevel;
    std::uint32_t levelCount;
    std::uint32_t samples;  // Entries per pixel of a visibility buffer.
    std::uint32_t padding;
};
static_assert(sizeof(ReductionUniform) == 24);

wgpu::TextureView levelView(const wgpu::Texture& texture, std::uint32_t level) {
    wgpu::TextureViewDescriptor descriptor{};
    descriptor.baseMipLevel = level;
    descriptor.mipLevelCount = 1;
    return texture.CreateView(&descriptor);
}

std::uint32_t powerOfTwoAtLeast(std::uint32_t value) {
    std::uint32_t power = 1;
    while (power < value) {
        power *= 2;
    }
    return power;
}

}  // namespace

Result<DepthPyramid> DepthPyramid::create(const wgpu::Device& device,
                                          shaders::ShaderLibrary& shaders,
                                          const wgpu::Texture& depth) {
    return build(device, shaders, {depth, nullptr, depth.GetWidth(), depth.GetHeight(), 1});
}

Result<DepthPyramid> DepthPyramid::createFromVisibility(const wgpu::Device& device,
                                                        shaders::ShaderLibrary& shaders,
                                                        const wgpu::Buffer& visibility,
                                                        std::uint32_t width,
                                                        std::uint32_t height) {
    // One entry per pixel, or one per sample where the strategy keeps several.
    const std::uint64_t pixelBytes = std::uint64_t(width) * height * 8;
    const auto samples = std::uint32_t(
        std::max<std::uint64_t>(pixelBytes == 0 ? 1 : visibility.GetSize() / pixelBytes, 1));
    return build(device, shaders, {nullptr, visibility, width, height, samples});
}

Result<DepthPyramid> DepthPyramid::build(const wgpu::Device& device,
                                         shaders::ShaderLibrary& shaders,
                                         const Source& source) {
    DepthPyramid pyramid;
    pyramid.mDepth = source.depth;
    pyramid.mVisibility = source.visibility;
    pyramid.mWidth = source.width;
    pyramid.mHeight = source.height;
    std::set<std::string, std::less<>> flags;
    if (source.visibility) {
        flags.insert("VISIBILITY_BUFFER");
    } else if (source.depth.GetSampleCount() > 1) {
        flags.insert("MULTISAMPLED");
    }
    ENCORE_TRY_ASSIGN(auto module, shaders.module("depth_pyramid.wgsl", flags));
    auto computePipeline = [&](const char* entryPoint) {
        wgpu::ComputePipelineDescriptor descriptor{};
        descriptor.label = entryPoint;
        descriptor.compute.module = module;
        descriptor.compute.entryPoint = entryPoint;
        return device.CreateComputePipeline(&descriptor);  // Layout from the entry point.
    };
    pyramid.mReduceDepth = computePipeline("reduceDepth");
    pyramid.mReduceLevels = computePipeline("reduceLevels");

    const std::uint32_t depthWidth = source.width;
    const std::uint32_t depthHeight = source.height;
    wgpu::TextureDescriptor descriptor{};
    descriptor.label = "depth pyramid";
    descriptor.size = {powerOfTwoAtLeast(levelSize(depthWidth, 0)),
                       powerOfTwoAtLeast(levelSize(depthHeight, 0)), 1};
    descriptor.format = wgpu::TextureFormat::R32Float;
    descriptor.mipLevelCount = std::min(
        kMaxLevels, static_cast<std::uint32_t>(
                        std::bit_width(std::max(descriptor.size.width, descriptor.size.height))));
    descriptor.usage = wgpu::TextureUsage::StorageBinding | wgpu::TextureUsage::TextureBinding |
                       wgpu::TextureUsage::CopySrc;  // Read back by tests.
    pyramid.mPyramid = device.CreateTexture(&descriptor);
    pyramid.mView = pyramid.mPyramid.CreateView();
    pyramid.mLevelCount = descriptor.mipLevelCount;

    // WebGPU forbids two writable bindings of one subresource: each unused binding of the last
    // dispatch (at most its last three) gets a level of its own.
    descriptor.label = "depth pyramid: unused levels";
    descriptor.size = {4, 4, 1};
    descriptor.mipLevelCount = kLevelsPerDispatch - 1;
    descriptor.usage = wgpu::TextureUsage::StorageBinding;
    pyramid.mUnusedLevels = device.CreateTexture(&descriptor);

    const std::uint32_t dispatches =
        (pyramid.mLevelCount + kLevelsPerDispatch - 1) / kLevelsPerDispatch;
    std::vector<std::uint8_t> uniforms(dispatches * kUniformStride);
    // Level 0's source: the depth texture's view, or the visibility buffer.
    const gpu::BindingResource depthSource =
        source.visibility ? gpu::BindingResource(0, source.visibility)
                          : gpu::BindingResource(0, source.depth.CreateView());
    for (std::uint32_t dispatch = 0; dispatch < dispatches; ++dispatch) {
        const std::uint32_t firstLevel = dispatch * kLevelsPerDispatch;
        const ReductionUniform uniform{
            {depthWidth, depthHeight},
            firstLevel,
            std::min(kLevelsPerDispatch, pyramid.mLevelCount - firstLevel),
            source.samples,
            0};
        std::memcpy(&uniforms[dispatch * kUniformStride], &uniform, sizeof(uniform));
    }
    pyramid.mUniforms = gpu::createBufferFrom<std::uint8_t>(device, wgpu::BufferUsage::Uniform,
                                                            uniforms, "depth pyramid reductions");
    for (std::uint32_t dispatch = 0; dispatch < dispatches; ++dispatch) {
        const std::uint32_t firstLevel = dispatch * kLevelsPerDispatch;
        std::vector<gpu::BindingResource> resources = {
            firstLevel == 0 ? depthSource
                            : gpu::BindingResource(1, levelView(pyramid.mPyramid, firstLevel - 1)),
            {2, pyramid.mUniforms, dispatch * kUniformStride, sizeof(ReductionUniform)}};
        for (std::uint32_t step = 0; step < kLevelsPerDispatch; ++step) {
            const std::uint32_t level = firstLevel + step;
            resources.emplace_back(3 + step, level < pyramid.mLevelCount
                                                 ? levelView(pyramid.mPyramid, level)
                                                 : levelView(pyramid.mUnusedLevels, step - 1));
        }
        const wgpu::ComputePipeline& pipeline =
            firstLevel == 0 ? pyramid.mReduceDepth : pyramid.mReduceLevels;
        const wgpu::BindGroup group = gpu::makeBindGroup(device, pipeline.GetBindGroupLayout(0),
                                                         resources, "depth pyramid reduction");
        pyramid.mReductions.push_back({group, firstLevel,
                                       (levelSize(depthWidth, firstLevel) + kTile - 1) / kTile,
                                       (levelSize(depthHeight, firstLevel) + kTile - 1) / kTile});
    }
    return pyramid;
}

void DepthPyramid::encode(const wgpu::ComputePassEncoder& pass) const {
    for (const Reduction& reduction : mReductions) {
        if (reduction.firstLevel <= kLevelsPerDispatch) {  // The first two change pipelines.
            pass.SetPipeline(reduction.firstLevel == 0 ? mReduceDepth : mReduceLevels);
        }
        pass.SetBindGroup(0, reduction.bindGroup);
        pass.DispatchWorkgroups(reduction.workgroupsX, reduction.workgroupsY);
    }
}

}  // namespace encore::render
