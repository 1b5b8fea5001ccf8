#pragma once

// Segmentation ids exact in a multisampled frame (RenderTargetOptions::exactIds). The resolve
// averages a pixel's samples: at an object's edge it would blend two ids (or an id and the
// background's 0) into a value that is neither. After the scene passes this pass reads sample 0
// of the multisampled texture, which the scene passes then store, and writes its id into the
// resolved texture's two id channels, times the resolved coverage (sample_ids.wgsl); depth,
// colour and coverage keep their average. Readers divide by the coverage as before and get the
// id of one sample: one that was drawn.

#include <webgpu/webgpu_cpp.h>

#include "encore/core/Result.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

// Where a texture holds the id (id % 256, then id / 256).
enum class IdChannels {
    RedGreen,   // A frame drawn through a segmentation channel (DebugChannel::Segment*).
    GreenBlue,  // The DepthAndId pass target (PassTargets.h), after depth.
};

class SampleIdPass {
  public:
    // For rgba16float textures of 4 samples.
    static Result<SampleIdPass> create(const wgpu::Device& device,
                                       shaders::ShaderLibrary& shaders,
                                       IdChannels channels);

    // Reads `multisampled` (TextureBinding, stored by the scene passes) from now on.
    void bindSource(const wgpu::Device& device, const wgpu::TextureView& multisampled);
    // Writes the ids of the bound source into `resolved`, its resolve.
    void encode(const wgpu::CommandEncoder& commands, const wgpu::TextureView& resolved) const;

  private:
    SampleIdPass() = default;

    wgpu::BindGroupLayout mLayout;
    wgpu::RenderPipeline mPipeline;
    wgpu::BindGroup mBindGroup;
};

}  // namespace encore::render
