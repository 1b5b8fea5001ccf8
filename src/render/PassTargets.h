#pragma once

// encore batch's passes drawn in the colour frame's own render pass (RendererOptions::
// passTargets, docs/batch.md#passes): four colour targets beside the scene colour, written by
// mesh.wgsl's PASS_TARGETS variant. Each holds what a debug channel's frame would hold in the
// HDR target (the same format, blending and resolve, so the same values): the normal, the
// albedo, the material values, and depth with the segmentation id split in two. The first three
// are then converted to RGBA8 sRGB by the tone-mapping pass with tone mapping off, as the debug
// channels' frames are, and every image is read back from its own texture. With the target's
// exactIds and 4 samples, the ids come from one sample of each pixel (SampleIdPass.h).

#include <webgpu/webgpu_cpp.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/RenderTarget.h"
#include "encore/render/Renderer.h"
#include "render/SampleIdPass.h"
#include "render/SceneColorTargets.h"
#include "render/ToneMapper.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class PassTargetTextures {
  public:
    // For `target` (HDR, any sample count).
    static Result<PassTargetTextures> create(const wgpu::Device& device,
                                             const wgpu::Queue& queue,
                                             shaders::ShaderLibrary& shaders,
                                             const RenderTarget& target);

    // Colour attachments 1..4 of a scene pass whose attachment 0 is `color`, written from
    // `attachments[0]` on: they load, store and resolve as it does, and clear to transparent
    // black (the debug channels' background). With exact ids the multisampled DepthAndId is
    // always stored, for encodeImages.
    void fillAttachments(
        const wgpu::RenderPassColorAttachment& color,
        std::span<wgpu::RenderPassColorAttachment, kPassTargetCount> attachments) const;
    // After the scene passes: converts the resolved normal, albedo and material targets to their
    // RGBA8 images and, with exact ids, writes sample 0's ids into the resolved DepthAndId.
    void encodeImages(const wgpu::CommandEncoder& commands) const;

    // Normal, Albedo, Material: RGBA8 sRGB; DepthAndId: the resolved rgba16float target.
    const wgpu::Texture& texture(PassImage image) const;
    // For a compute pass: the 8-bit images through an RGBA8Unorm view (the target's
    // RenderTargetOptions::bytesViews), DepthAndId as it is.
    const wgpu::TextureView& bytesView(PassImage image) const;

  private:
    PassTargetTextures() = default;

    struct Target {
        wgpu::Texture multisampled;  // Only with a multisampled target.
        wgpu::TextureView multisampledView;
        wgpu::Texture resolved;  // rgba16float.
        wgpu::TextureView resolvedView;
        wgpu::Texture image;  // RGBA8 sRGB (not for DepthAndId).
        wgpu::TextureView imageView;
        wgpu::TextureView bytesView;  // RGBA8Unorm, with RenderTargetOptions::bytesViews.
    };
    std::array<Target, kPassTargetCount> mTargets;
    // One tone mapper per 8-bit image (each binds its own source), tone mapping off.
    std::vector<ToneMapper> mConverters;
    std::optional<SampleIdPass> mIds;  // Exact ids at 4 samples only.
};

// ShaderVariantKey::passTargets for `targets` (0: none).
std::uint8_t passTargetsVariant(PassTargets targets);

}  // namespace encore::render
