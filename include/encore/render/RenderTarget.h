#pragma once

// An offscreen colour + depth target. Colour is RGBA8UnormSrgb (shading happens in linear space
// and is encoded on write); with sampleCount 4 the pass renders into a multisampled texture and
// resolves into the readable colour texture.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

#include "encore/core/Result.h"

namespace encore::render {

struct RenderTargetOptions {
    std::uint32_t width = 1280;
    std::uint32_t height = 720;
    std::uint32_t sampleCount = 1;  // 1 or 4.
};

class RenderTarget {
  public:
    static constexpr wgpu::TextureFormat kColorFormat = wgpu::TextureFormat::RGBA8UnormSrgb;
    static constexpr wgpu::TextureFormat kDepthFormat = wgpu::TextureFormat::Depth32Float;

    static Result<RenderTarget> create(const wgpu::Device& device,
                                       const RenderTargetOptions& options);

    std::uint32_t width() const { return mOptions.width; }
    std::uint32_t height() const { return mOptions.height; }
    std::uint32_t sampleCount() const { return mOptions.sampleCount; }
    float aspect() const { return float(mOptions.width) / float(mOptions.height); }

    // The single-sampled texture that holds the final image (CopySrc).
    const wgpu::Texture& colorTexture() const { return mColor; }

    // Attachments for a pass that clears colour to `clearColor` and depth to 1.
    wgpu::RenderPassColorAttachment colorAttachment(const wgpu::Color& clearColor) const;
    wgpu::RenderPassDepthStencilAttachment depthAttachment() const;

  private:
    RenderTargetOptions mOptions;
    wgpu::Texture mColor;
    wgpu::Texture mMultisampledColor;
    wgpu::Texture mDepth;
    wgpu::TextureView mColorView;
    wgpu::TextureView mMultisampledColorView;
    wgpu::TextureView mDepthView;
};

}  // namespace encore::render
