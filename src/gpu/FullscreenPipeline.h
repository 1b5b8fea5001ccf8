#pragma once

// The render pipeline of a fullscreen pass: one triangle, three vertices and no vertex buffer,
// that covers the target (its vertex shader places them from the vertex index), and a fragment
// shader that writes one colour attachment. Tone mapping, presenting, mipmap downsampling and the
// environment background are all such passes; each draws with pass.Draw(3).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>

namespace encore::gpu {

struct FullscreenPipelineDescriptor {
    wgpu::StringView label;
    wgpu::ShaderModule module;  // Holds both entry points.
    wgpu::StringView vertexEntryPoint = "vertexMain";
    wgpu::StringView fragmentEntryPoint = "fragmentMain";
    // Null: the layout WebGPU derives from the module (then only its bind groups fit).
    wgpu::PipelineLayout layout;
    wgpu::TextureFormat colorFormat = wgpu::TextureFormat::Undefined;
    // Without one, the fragment's colour replaces the target's.
    std::optional<wgpu::BlendState> blend;
    // The channels written; the others keep the target's values.
    wgpu::ColorWriteMask writeMask = wgpu::ColorWriteMask::All;
    // For a pass that has a depth attachment (and samples): the triangle neither tests nor
    // writes depth. Undefined: a pass without depth.
    wgpu::TextureFormat depthFormat = wgpu::TextureFormat::Undefined;
    // With a depth format: the fragment's frag_depth is written (always, untested).
    bool writesDepth = false;
    std::uint32_t sampleCount = 1;
    // More colour targets of colorFormat after the first, which the pass has and the fragment
    // shader does not write (a scene pass with pass targets, render/PassTargets.h).
    std::uint32_t untouchedTargets = 0;
};

wgpu::RenderPipeline makeFullscreenPipeline(const wgpu::Device& device,
                                            const FullscreenPipelineDescriptor& descriptor);

// Records a render pass that draws `pipeline`'s triangle over all of `target` (one colour
// attachment, no depth) with `bindGroup` as group 0. Every texel is drawn, so the target's
// previous contents are cleared rather than loaded, unless `load` (a pipeline that blends with
// them or writes some channels only). `timestamps` may be null.
void encodeFullscreenPass(const wgpu::CommandEncoder& encoder,
                          const wgpu::TextureView& target,
                          const wgpu::RenderPipeline& pipeline,
                          const wgpu::BindGroup& bindGroup,
                          wgpu::StringView label,
                          const wgpu::PassTimestampWrites* timestamps = nullptr,
                          bool load = false);

}  // namespace encore::gpu
