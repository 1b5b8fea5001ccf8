#pragma once

// The last pass of a frame: exposure, tone mapping and the background, from the render target's
// linear HDR scene colour to its sRGB output (tone_mapping.wgsl). Its parameters live in a
// uniform buffer, so changing exposure, operator or background never touches the scene's
// recorded bundles.

#include <webgpu/webgpu_cpp.h>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "encore/render/RenderTarget.h"
#include "encore/shaders/ShaderLibrary.h"

namespace encore::render {

enum class ToneMapping : std::uint32_t {
    None,        // Linear, clamped at 1.
    PbrNeutral,  // Khronos PBR Neutral (the default, as the Khronos Sample Renderer).
    AcesHill,    // ACES filmic, Stephen Hill's fit.
};

enum class BackgroundKind : std::uint32_t {
    Color,        // An opaque colour behind the scene.
    Transparent,  // Alpha 0 where nothing is drawn; colours are straight (not premultiplied).
    Environment,  // The environment map, drawn by EnvironmentBackground and tone mapped.
};

struct ToneMappingOptions {
    ToneMapping toneMapping = ToneMapping::PbrNeutral;
    float exposure = 1.0f;  // Multiplies linear colour before tone mapping.
    BackgroundKind background = BackgroundKind::Color;
    // Linear RGB of BackgroundKind::Color; the default is a neutral dark grey.
    glm::vec3 backgroundColor{0.05f, 0.05f, 0.06f};
};

class ToneMapper {
  public:
    static Result<ToneMapper> create(const wgpu::Device& device, const wgpu::Queue& queue,
                                     shaders::ShaderLibrary& shaders, const RenderTarget& target,
                                     const ToneMappingOptions& options);

    void setOptions(const ToneMappingOptions& options);
    const ToneMappingOptions& options() const { return mOptions; }

    // Reads `target`'s resolved HDR scene colour, writes its output.
    void encode(const wgpu::CommandEncoder& commands, const RenderTarget& target) const;

  private:
    ToneMapper() = default;

    wgpu::Queue mQueue;
    wgpu::RenderPipeline mPipeline;
    wgpu::Buffer mUniform;
    wgpu::BindGroup mBindGroup;
    ToneMappingOptions mOptions;
};

// The environment behind the scene (sky.wgsl): drawn at the start of every scene pass, with
// the frame bind group, so it follows each view's camera. Not counted as a strategy's call.
class EnvironmentBackground {
  public:
    static Result<EnvironmentBackground> create(const wgpu::Device& device,
                                                shaders::ShaderLibrary& shaders,
                                                const wgpu::BindGroupLayout& frameLayout,
                                                wgpu::TextureFormat colorFormat,
                                                wgpu::TextureFormat depthFormat,
                                                std::uint32_t sampleCount);

    void draw(const wgpu::RenderPassEncoder& pass, const wgpu::BindGroup& frame) const;

  private:
    wgpu::RenderPipeline mPipeline;
};

}  // namespace encore::render
