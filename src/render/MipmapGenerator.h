#pragma once

// Fills the mip chain of a 2D texture on the GPU from its level 0 (src/shaders/mipmap.wgsl).
//
// Each level is drawn from the previous one by a render pass with a full-screen triangle and a
// linear sampler. Render passes rather than compute: sRGB formats cannot be storage textures,
// and sampling an sRGB view while writing an sRGB attachment averages in linear space, which
// is what a correct downsample of colour needs. One pipeline is created per texture format and
// kept for later textures of that format.

#include <webgpu/webgpu_cpp.h>

#include <unordered_map>

#include "encore/core/Result.h"
#include "gpu/StageTimestamps.h"
#include "render/MipChain.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class MipmapGenerator {
  public:
    static Result<MipmapGenerator> create(const wgpu::Device& device,
                                          shaders::ShaderLibrary& shaders);

    // Records into `encoder` the passes that fill levels 1..mipLevelCount-1 of `texture` from
    // level 0, which must hold its data by the time the commands execute (a Queue::WriteTexture
    // before the submit is enough). The texture must be 2D with one layer and have
    // TextureBinding and RenderAttachment usage and a renderable, filterable float format.
    Result<void> generate(const wgpu::CommandEncoder& encoder, const wgpu::Texture& texture);

    std::size_t pipelineCount() const { return mPipelines.size(); }

    // Times the passes of later generate() calls as `stage` (nullptr: untimed).
    void setTimestamps(gpu::StageTimestamps* timestamps, std::uint32_t stage) {
        mTimestamps = timestamps;
        mStage = stage;
    }

  private:
    MipmapGenerator() = default;
    const wgpu::RenderPipeline& pipeline(wgpu::TextureFormat format);

    wgpu::Device mDevice;
    wgpu::ShaderModule mModule;
    wgpu::Sampler mSampler;
    wgpu::BindGroupLayout mLayout;
    wgpu::PipelineLayout mPipelineLayout;
    std::unordered_map<wgpu::TextureFormat, wgpu::RenderPipeline> mPipelines;
    gpu::StageTimestamps* mTimestamps = nullptr;
    std::uint32_t mStage = 0;
};

}  // namespace encore::render
