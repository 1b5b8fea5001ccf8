#pragma once

// An offscreen target with depth. By default scenes render straight into the readable
// RGBA8UnormSrgb output, their shaders applying the display transform as they shade (one pass
// per frame). With `hdr`, scenes render into a linear HDR colour texture (rgba16float, alpha =
// coverage) and a tone-mapping pass then writes the output (ToneMapper): for a transparent
// background (straight alpha needs the coverage) and for reading the linear colour back. With
// sampleCount 4 the scene pass renders into multisampled textures and resolves into the
// single-sampled scene texture.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

#include "encore/core/Result.h"

namespace encore::render {

struct RenderTargetOptions {
    std::uint32_t width = 1280;
    std::uint32_t height = 720;
    std::uint32_t sampleCount = 1;  // 1 or 4.
    bool hdr = false;
    // The pass images (PassTargets.h) can also be read as bytes by a compute pass, through
    // RGBA8Unorm views: encore batch's PNG rows (batch/PngRowsPass).
    bool bytesViews = false;
    // Segmentation ids exact at 4 samples (encore batch --segmentation): the multisampled HDR
    // scene colour and DepthAndId pass target are also TextureBinding, and the frames that draw
    // ids (the segmentation channels, pass targets) take them from one sample of each pixel, not
    // from the resolve's average (render/SampleIdPass.h). Nothing changes at one sample.
    bool exactIds = false;

    bool operator==(const RenderTargetOptions&) const = default;
};

class RenderTarget {
  public:
    static constexpr wgpu::TextureFormat kColorFormat = wgpu::TextureFormat::RGBA8UnormSrgb;
    // The output texture's own format: kColorFormat's bytes, without sRGB encoding.
    static constexpr wgpu::TextureFormat kBytesFormat = wgpu::TextureFormat::RGBA8Unorm;
    static constexpr wgpu::TextureFormat kHdrFormat = wgpu::TextureFormat::RGBA16Float;
    static constexpr wgpu::TextureFormat kDepthFormat = wgpu::TextureFormat::Depth32Float;

    static Result<RenderTarget> create(const wgpu::Device& device,
                                       const RenderTargetOptions& options);

    std::uint32_t width() const { return mOptions.width; }
    std::uint32_t height() const { return mOptions.height; }
    std::uint32_t sampleCount() const { return mOptions.sampleCount; }
    bool hdr() const { return mOptions.hdr; }
    float aspect() const { return float(mOptions.width) / float(mOptions.height); }

    // The format scene pipelines render into: kHdrFormat, or kColorFormat without HDR.
    wgpu::TextureFormat sceneFormat() const { return mOptions.hdr ? kHdrFormat : kColorFormat; }

    // The single-sampled texture that holds the final image: kBytesFormat, drawn through
    // kColorFormat views (outputView), CopySrc.
    const wgpu::Texture& colorTexture() const { return mOutput; }
    // The resolved scene colour (the output itself without HDR; TextureBinding with HDR).
    const wgpu::Texture& sceneTexture() const { return mScene; }
    const wgpu::TextureView& sceneView() const { return mSceneView; }
    // The scene colour as a write-only storage texture for compute (Strategy::composeFrame):
    // kBytesFormat (a shader encodes sRGB itself), or kHdrFormat with HDR.
    const wgpu::TextureView& sceneStorageView() const { return mSceneStorageView; }
    // The multisampled scene colour (null at one sample); TextureBinding with exactIds.
    const wgpu::TextureView& multisampledSceneView() const { return mMultisampledSceneView; }
    const wgpu::TextureView& outputView() const { return mOutputView; }
    // The output's bytes as RGBA8Unorm (no sRGB decoding when sampled).
    const wgpu::TextureView& outputBytesView() const { return mOutputBytesView; }
    const RenderTargetOptions& options() const { return mOptions; }
    // Depth32Float with the colour's sample count; also TextureBinding (DepthPyramid reads it).
    const wgpu::Texture& depthTexture() const { return mDepth; }

    // Attachments for a scene pass that clears colour to `clearColor` and depth to 1.
    wgpu::RenderPassColorAttachment colorAttachment(const wgpu::Color& clearColor) const;
    // The resolved scene texture itself as the attachment (one sample, stored), for passes
    // that draw it directly (Strategy::composesResolved).
    wgpu::RenderPassColorAttachment resolvedColorAttachment(const wgpu::Color& clearColor) const;
    wgpu::RenderPassDepthStencilAttachment depthAttachment() const;

  private:
    RenderTargetOptions mOptions;
    wgpu::Texture mScene;
    wgpu::Texture mMultisampledScene;
    wgpu::Texture mOutput;
    wgpu::Texture mDepth;
    wgpu::TextureView mSceneView;
    wgpu::TextureView mSceneStorageView;
    wgpu::TextureView mMultisampledSceneView;
    wgpu::TextureView mOutputView;
    wgpu::TextureView mOutputBytesView;
    wgpu::TextureView mDepthView;
};

}  // namespace encore::render
