#include "render/ToneMapper.h"

#include <cmath>

#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"

namespace encore::render {

namespace {

// struct ToneMapping of tone_mapping.wgsl, byte for byte.
struct ToneMappingUniform {
    float exposure;
    std::uint32_t toneMapping;
    std::uint32_t background;
    std::uint32_t padding;
    float backgroundColor[4];
};
static_assert(sizeof(ToneMappingUniform) == 32);

}  // namespace

Result<ToneMapper> ToneMapper::create(const wgpu::Device& device,
                                      const wgpu::Queue& queue,
                                      shaders::ShaderLibrary& shaders,
                                      const RenderTarget& target,
                                      const ToneMappingOptions& options) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("tone_mapping.wgsl"));
    ToneMapper mapper;
    mapper.mQueue = queue;

    mapper.mLayout = gpu::makeBindGroupLayout(
        device,
        {gpu::LayoutEntry::uniform(0, wgpu::ShaderStage::Fragment, sizeof(ToneMappingUniform)),
         // Read with textureLoad only, so the HDR format need not be filterable.
         gpu::LayoutEntry::texture(1, wgpu::ShaderStage::Fragment,
                                   wgpu::TextureSampleType::UnfilterableFloat)},
        "tone mapping");
    mapper.mPipeline = gpu::makeFullscreenPipeline(
        device, {.label = "tone mapping",
                 .module = module,
                 .layout = gpu::makePipelineLayout(device, {mapper.mLayout}),
                 .colorFormat = RenderTarget::kColorFormat});

    mapper.mUniform =
        gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                          sizeof(ToneMappingUniform), "tone mapping");
    mapper.bindTarget(device, target);
    mapper.setOptions(options);
    return mapper;
}

void ToneMapper::bindTarget(const wgpu::Device& device, const RenderTarget& target) {
    bindSource(device, target.sceneView());
}

void ToneMapper::bindSource(const wgpu::Device& device, const wgpu::TextureView& source) {
    mBindGroup = gpu::makeBindGroup(device, mLayout,
                                    {{0, mUniform, 0, sizeof(ToneMappingUniform)}, {1, source}},
                                    "tone mapping");
}

void ToneMapper::setOptions(const ToneMappingOptions& options) {
    mOptions = options;
    ToneMappingUniform uniform{};
    uniform.exposure = options.exposure;
    uniform.toneMapping = static_cast<std::uint32_t>(options.toneMapping);
    uniform.background = static_cast<std::uint32_t>(options.background);
    for (int i = 0; i < 3; ++i) {
        uniform.backgroundColor[i] = options.backgroundColor[i];
    }
    uniform.backgroundColor[3] = 1.0f;
    mQueue.WriteBuffer(mUniform, 0, &uniform, sizeof(uniform));
}

void ToneMapper::encode(const wgpu::CommandEncoder& commands,
                        const RenderTarget& target,
                        const wgpu::PassTimestampWrites* timestamps) const {
    encode(commands, target.outputView(), timestamps);
}

void ToneMapper::encode(const wgpu::CommandEncoder& commands,
                        const wgpu::TextureView& output,
                        const wgpu::PassTimestampWrites* timestamps) const {
    gpu::encodeFullscreenPass(commands, output, mPipeline, mBindGroup, "encore tone mapping",
                              timestamps);
}

Result<EnvironmentBackground> EnvironmentBackground::create(
    const wgpu::Device& device,
    shaders::ShaderLibrary& shaders,
    const wgpu::BindGroupLayout& frameLayout,
    wgpu::TextureFormat colorFormat,
    wgpu::TextureFormat depthFormat,
    std::uint32_t sampleCount,
    std::uint32_t passTargets) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("sky.wgsl"));
    EnvironmentBackground background;
    background.mPipeline = gpu::makeFullscreenPipeline(
        device, {.label = "environment background",
                 .module = module,
                 .layout = gpu::makePipelineLayout(device, {frameLayout}),
                 .colorFormat = colorFormat,
                 .depthFormat = depthFormat,
                 .sampleCount = sampleCount,
                 .untouchedTargets = passTargets});
    return background;
}

void EnvironmentBackground::draw(const wgpu::RenderPassEncoder& pass,
                                 const wgpu::BindGroup& frame) const {
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, frame);
    pass.Draw(3);
}

}  // namespace encore::render
