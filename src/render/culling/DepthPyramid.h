#pragma once

// The depth pyramid that two-phase occlusion culling tests instances against (GpuCuller): an
// r32float mip chain of the farthest depth under each texel, built by a compute pass from the
// render target's depth after the first phase has drawn (depth_pyramid.wgsl). Level k holds
// ceil(depth size / 2^(k+1)) texels a side in the top-left corner of a texture that is a power
// of two a side, so that every texel reduces exactly 2x2 of the level below and one dispatch
// can build four levels; there are at most eight (down to 1x1 for targets up to 512 pixels). Built
// for one depth texture (or one visibility buffer): a resized target needs a new pyramid.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class DepthPyramid {
  public:
    DepthPyramid() = default;
    // `depth` is a Depth32Float texture with TextureBinding usage, single or multisampled.
    static Result<DepthPyramid> create(const wgpu::Device& device,
                                       shaders::ShaderLibrary& shaders,
                                       const wgpu::Texture& depth);

    // From the visibility strategy's buffer (VisibilityStrategy): `width` x `height` pixels, row
    // by row, each one or more (as many as the buffer's size holds) pairs of u32, the high word
    // ~depth bits, 0 where nothing was drawn (depth 1); a texel keeps the farthest of them.
    static Result<DepthPyramid> createFromVisibility(const wgpu::Device& device,
                                                     shaders::ShaderLibrary& shaders,
                                                     const wgpu::Buffer& visibility,
                                                     std::uint32_t width,
                                                     std::uint32_t height);

    bool builtFor(const wgpu::Texture& depth) const {
        return mDepth && mDepth.Get() == depth.Get();
    }
    bool builtFor(const wgpu::Buffer& visibility) const {
        return mVisibility && mVisibility.Get() == visibility.Get();
    }

    // Dispatches the reductions into `pass`, four levels each (each dispatch its own usage
    // scope, so a dispatch reads the level the one before it wrote last).
    void encode(const wgpu::ComputePassEncoder& pass) const;

    // The texels level `level` holds a side (the rest of the mip is unused).
    static std::uint32_t levelSize(std::uint32_t depthSize, std::uint32_t level) {
        const std::uint32_t texelPixels = 1u << (level + 1);
        return (depthSize + texelPixels - 1) / texelPixels;
    }

    // Every level, for textureLoad with an explicit level.
    const wgpu::TextureView& view() const { return mView; }
    const wgpu::Texture& texture() const { return mPyramid; }
    std::uint32_t levelCount() const { return mLevelCount; }
    std::uint32_t depthWidth() const { return mWidth; }
    std::uint32_t depthHeight() const { return mHeight; }

  private:
    // What level 0 reduces: a depth texture or a visibility buffer.
    struct Source {
        wgpu::Texture depth;
        wgpu::Buffer visibility;
        std::uint32_t width = 0;
        std::uint32_t height = 0;
        std::uint32_t samples = 1;  // Entries per pixel of the visibility buffer.
    };
    static Result<DepthPyramid> build(const wgpu::Device& device,
                                      shaders::ShaderLibrary& shaders,
                                      const Source& source);

    // One dispatch: up to four levels from firstLevel.
    struct Reduction {
        wgpu::BindGroup bindGroup;
        std::uint32_t firstLevel = 0;
        std::uint32_t workgroupsX = 0;
        std::uint32_t workgroupsY = 0;
    };

    wgpu::Texture mDepth;
    wgpu::Buffer mVisibility;
    std::uint32_t mWidth = 0;
    std::uint32_t mHeight = 0;
    wgpu::Texture mPyramid;
    wgpu::TextureView mView;
    wgpu::Buffer mUniforms;       // One Reduction uniform per dispatch.
    wgpu::Texture mUnusedLevels;  // Bound where a dispatch writes fewer than four levels.
    wgpu::ComputePipeline mReduceDepth;
    wgpu::ComputePipeline mReduceLevels;
    std::vector<Reduction> mReductions;
    std::uint32_t mLevelCount = 0;
};

}  // namespace encore::render
