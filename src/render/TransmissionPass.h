#pragma once

// KHR_materials_transmission, as the Khronos Sample Renderer draws it: the scene without its
// transmissive surfaces is drawn first (the strategy's usual pass), then copied into a
// mip-chained colour texture, and the transmissive surfaces are drawn in a pass of their own
// that samples it, refracted and blurred by roughness (transmission.wgsl).
//
// The copy's texture belongs to the GPU scene (created only when a material of the scene has
// transmission) and has the Sample Renderer's fixed size, 1024 x 1024, whatever the target's:
// its mip level for a roughness is the reference's, and the frame bind group that binds it
// never changes with the target's size, so recorded bundles stay valid across resizes. This
// class records the copy: the resolved scene colour drawn into level 0 (bilinear), then each
// level from the one above, every view and bind group made once. Frames of scenes without
// transmission never reach it: the Renderer skips the copy and the pass.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "gpu/GpuTimer.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class TransmissionPass {
  public:
    static constexpr std::uint32_t kSize = 1024;
    static constexpr wgpu::TextureFormat kFormat = wgpu::TextureFormat::RGBA16Float;

    // The texture transmissive surfaces sample: kSize square, kFormat, every mip level.
    static wgpu::Texture createBackground(const wgpu::Device& device);

    // Copies into `background` (from createBackground).
    static Result<TransmissionPass> create(const wgpu::Device& device,
                                           shaders::ShaderLibrary& shaders,
                                           const wgpu::Texture& background);

    const wgpu::Texture& background() const { return mBackground; }

    // Records the copy of `source` (a view of the target's resolved scene colour, sampled with
    // its sRGB decoding: RenderTarget::sceneView) into the background and its mip chain.
    // `timer` (may be null) times the passes.
    void encodeCopy(const wgpu::CommandEncoder& commands,
                    const wgpu::TextureView& source,
                    gpu::GpuTimer* timer);

    // Copies recorded so far (tests count that scenes without transmission make none).
    std::uint64_t copies() const { return mCopies; }

  private:
    wgpu::Device mDevice;
    wgpu::Texture mBackground;
    wgpu::RenderPipeline mPipeline;
    wgpu::BindGroupLayout mLayout;
    wgpu::Sampler mSampler;
    std::vector<wgpu::TextureView> mLevels;      // One view per mip level.
    std::vector<wgpu::BindGroup> mLevelSources;  // [i]: level i as the source of level i + 1.
    WGPUTextureView mSource = nullptr;           // The view mSourceGroup reads.
    wgpu::BindGroup mSourceGroup;
    std::uint64_t mCopies = 0;
};

}  // namespace encore::render
