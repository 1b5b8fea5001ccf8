#pragma once

// Copies a rendered image into a window's surface texture: a full-screen pass (present.wgsl)
// that reads the image (RenderTarget::outputView for an sRGB surface, outputBytesView for a
// linear one) and writes it so that the surface stores the same 8-bit values, converting
// between RGBA and BGRA order where the surface needs it.
// The scene's own passes and bundles are untouched: they keep rendering into the renderer's
// target, whose formats never depend on the window.

#include <webgpu/webgpu_cpp.h>

#include "encore/core/Result.h"
#include "shaders/ShaderLibrary.h"

namespace encore::view {

class Presenter {
  public:
    static Result<Presenter> create(const wgpu::Device& device,
                                    shaders::ShaderLibrary& shaders,
                                    wgpu::TextureFormat surfaceFormat);

    // Records the copy of `source` (a view the size of `target`) into `target`.
    void encode(const wgpu::CommandEncoder& commands,
                const wgpu::TextureView& source,
                const wgpu::TextureView& target);

  private:
    Presenter() = default;
    wgpu::Device mDevice;
    wgpu::RenderPipeline mPipeline;
    wgpu::BindGroupLayout mLayout;
    // Bound to the last source view; a resized target brings a new view and a new bind group.
    wgpu::TextureView mBoundSource;
    wgpu::BindGroup mBindGroup;
};

}  // namespace encore::view
