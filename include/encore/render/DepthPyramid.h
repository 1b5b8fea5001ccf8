#pragma once

// The depth pyramid that two-phase occlusion culling tests instances against (GpuCuller): an
// r32float mip chain of the farthest depth under each texel, built by compute passes from the
// render target's depth after the first phase has drawn (depth_pyramid.wgsl). Level 0 is half
// the depth's size (rounded down, as mips are); the chain ends at 1x1. Built for one depth
// texture: a resized target needs a new pyramid.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "encore/shaders/ShaderLibrary.h"

namespace encore::render {

class DepthPyramid {
  public:
    DepthPyramid() = default;
    // `depth` is a Depth32Float texture with TextureBinding usage, single or multisampled.
    static Result<DepthPyramid> create(const wgpu::Device& device, shaders::ShaderLibrary& shaders,
                                       const wgpu::Texture& depth);

    bool builtFor(const wgpu::Texture& depth) const { return mDepth && mDepth.Get() == depth.Get(); }

    // Dispatches the reductions, level by level, into `pass` (each dispatch its own usage scope,
    // so a level reads the one written before it).
    void encode(const wgpu::ComputePassEncoder& pass) const;

    // Every level, for textureLoad with an explicit level.
    const wgpu::TextureView& view() const { return mView; }
    const wgpu::Texture& texture() const { return mPyramid; }
    std::uint32_t levelCount() const { return static_cast<std::uint32_t>(mLevels.size()); }
    std::uint32_t depthWidth() const { return mDepth.GetWidth(); }
    std::uint32_t depthHeight() const { return mDepth.GetHeight(); }

  private:
    struct Level {
        wgpu::BindGroup bindGroup;
        std::uint32_t width = 0;
        std::uint32_t height = 0;
    };

    wgpu::Texture mDepth;
    wgpu::Texture mPyramid;
    wgpu::TextureView mView;
    wgpu::ComputePipeline mReduceDepth;
    wgpu::ComputePipeline mReduceLevel;
    std::vector<Level> mLevels;
};

}  // namespace encore::render
