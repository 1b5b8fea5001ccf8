#pragma once

// The last pass of a frame on an HDR render target: exposure, tone mapping and the background,
// from the target's linear HDR scene colour to its sRGB output (tone_mapping.wgsl). Targets
// without HDR need no pass: the scene shaders apply the same transform (SceneLighting). Its
// parameters live in a uniform buffer, so changing exposure, operator or background never touches
// the scene's recorded bundles.

#include <webgpu/webgpu_cpp.h>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "encore/render/RenderTarget.h"
#include "encore/render/RendererOptions.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class ToneMapper {
  public:
    static Result<ToneMapper> create(const wgpu::Device& device,
                                     const wgpu::Queue& queue,
                                     shaders::ShaderLibrary& shaders,
                                     const RenderTarget& target,
                                     const ToneMappingOptions& options);

    void setOptions(const ToneMappingOptions& options);
    // Reads `target`'s scene colour from now on (a resized target; same formats).
    void bindTarget(const wgpu::Device& device, const RenderTarget& target);
    // Reads `source` (an rgba16float view) from now on instead.
    void bindSource(const wgpu::Device& device, const wgpu::TextureView& source);
    const ToneMappingOptions& options() const { return mOptions; }

    // Reads `target`'s resolved HDR scene colour, writes its output.
    // `timestamps`: the pass's timestamp writes, or nullptr (untimed).
    void encode(const wgpu::CommandEncoder& commands,
                const RenderTarget& target,
                const wgpu::PassTimestampWrites* timestamps = nullptr) const;
    // The same into `output` (RenderTarget::kColorFormat).
    void encode(const wgpu::CommandEncoder& commands,
                const wgpu::TextureView& output,
                const wgpu::PassTimestampWrites* timestamps = nullptr) const;

  private:
    ToneMapper() = default;

    wgpu::Queue mQueue;
    wgpu::RenderPipeline mPipeline;
    wgpu::BindGroupLayout mLayout;
    wgpu::Buffer mUniform;
    wgpu::BindGroup mBindGroup;
    ToneMappingOptions mOptions;
};

// The environment behind the scene (sky.wgsl): drawn at the start of every scene pass, with
// the frame bind group, so it follows each view's camera. With `passTargets`, the passes have
// that many more colour targets of the same format, which the sky leaves as they are. Not counted
// as a strategy's call.
class EnvironmentBackground {
  public:
    static Result<EnvironmentBackground> create(const wgpu::Device& device,
                                                shaders::ShaderLibrary& shaders,
                                                const wgpu::BindGroupLayout& frameLayout,
                                                wgpu::TextureFormat colorFormat,
                                                wgpu::TextureFormat depthFormat,
                                                std::uint32_t sampleCount,
                                                std::uint32_t passTargets = 0);

    void draw(const wgpu::RenderPassEncoder& pass, const wgpu::BindGroup& frame) const;

  private:
    wgpu::RenderPipeline mPipeline;
};

}  // namespace encore::render
