#pragma once

// Environment owns the GPU side of image-based lighting: from an equirectangular HDR panorama
// it computes, on the GPU with compute shaders,
//  - a specular cube map prefiltered for the GGX distribution, one roughness per mip level
//    (roughness = level / (levelCount - 1), level 0 a mirror);
//  - a diffuse irradiance cube map holding, for each normal n, the cosine-weighted average of
//    the radiance over the hemisphere around n (so diffuse = albedo * irradiance(n));
//  - the split-sum BRDF lookup table: for (NdotV, roughness) in [0,1]^2, red and green are the
//    scale and bias applied to F0 for GGX with height-correlated Smith visibility, blue the
//    directional albedo of the Charlie sheen lobe (KHR_materials_sheen).
// Directions follow HdrImage's panorama convention in Encore's world space (right-handed,
// +Y up); a rotation about +Y is applied by the shaders at lookup, not baked in here.
//
// The scene shaders sample none of those three: a last pass packs them into the environment
// atlas (EnvironmentAtlas.h), one texture of one subresource, which is all a frame binds. The
// cube maps and the table stay as the atlas's sources (a later load() writes them again).
//
// load() writes a new panorama into the same textures, so bind groups that reference the
// atlas stay valid: changing the environment never re-records a render bundle.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <memory>

#include "encore/core/Result.h"
#include "encore/image/HdrImage.h"
#include "encore/render/RendererOptions.h"
#include "render/EnvironmentAtlas.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class Environment {
  public:
    static constexpr wgpu::TextureFormat kCubeFormat = wgpu::TextureFormat::RGBA16Float;

    static Result<Environment> create(const wgpu::Device& device,
                                      const wgpu::Queue& queue,
                                      shaders::ShaderLibrary& shaders,
                                      const image::HdrImage& panorama,
                                      const EnvironmentOptions& options = {});

    Environment(Environment&&) noexcept = default;
    Environment& operator=(Environment&&) noexcept = default;
    Environment(const Environment&) = delete;
    Environment& operator=(const Environment&) = delete;

    // Recomputes every map from `panorama` into the existing textures (bind groups stay valid).
    Result<void> load(const image::HdrImage& panorama);

    // What the scene shaders sample: the atlas, through sampler() (linear, clamped to edge).
    const wgpu::TextureView& atlasView() const { return mAtlasView; }
    const wgpu::Texture& atlasTexture() const { return mAtlas; }
    const EnvironmentAtlasLayout& atlasLayout() const { return mAtlasLayout; }
    const wgpu::Sampler& sampler() const { return mSampler; }
    std::uint32_t specularLevels() const { return mOptions.specularLevels; }

    // The atlas's sources, for tests and tools (CopySrc): cube views with their mips, the 2D
    // table.
    const wgpu::TextureView& specularView() const { return mSpecularView; }
    const wgpu::TextureView& irradianceView() const { return mIrradianceView; }
    const wgpu::TextureView& brdfLutView() const { return mLutView; }
    const wgpu::Texture& specularTexture() const { return mSpecular; }
    const wgpu::Texture& irradianceTexture() const { return mIrradiance; }
    const wgpu::Texture& brdfLutTexture() const { return mLut; }

    // Wall-clock milliseconds the last create() or load() took, GPU work included.
    double lastBuildMilliseconds() const { return mLastBuildMilliseconds; }

    // The panorama of the last create() or load(), and the options: enough to build the same
    // environment again on another device (after a device loss).
    const image::HdrImage& panorama() const { return *mPanorama; }
    const EnvironmentOptions& options() const { return mOptions; }

  private:
    Environment() = default;
    struct Pipelines;
    struct ParameterSlots;
    Result<void> build(const image::HdrImage& panorama, bool withLut);
    // The steps of build(): the panorama as a half-float texture; the dispatches' parameters;
    // the compute pass that fills the source, specular and irradiance cubes and the LUT; the
    // mirror level's copy and the pass that packs them all into the atlas.
    wgpu::Texture uploadPanorama(const image::HdrImage& panorama) const;
    ParameterSlots writeParameters() const;
    void encodeMaps(const wgpu::CommandEncoder& encoder,
                    const wgpu::Texture& panoramaTexture,
                    const ParameterSlots& slots,
                    bool withLut) const;
    void encodeAtlas(const wgpu::CommandEncoder& encoder,
                     const ParameterSlots& slots,
                     bool withLut) const;

    wgpu::Device mDevice;
    wgpu::Queue mQueue;
    shaders::ShaderLibrary* mShaders = nullptr;
    EnvironmentOptions mOptions;
    wgpu::Texture mSpecular;
    wgpu::Texture mIrradiance;
    wgpu::Texture mLut;
    wgpu::TextureView mSpecularView;
    wgpu::TextureView mIrradianceView;
    wgpu::TextureView mLutView;
    wgpu::Texture mAtlas;
    wgpu::TextureView mAtlasView;
    EnvironmentAtlasLayout mAtlasLayout;
    wgpu::Sampler mSampler;
    // Shared so the class stays movable with Pipelines defined only in Environment.cpp.
    std::shared_ptr<const Pipelines> mPipelines;
    // The panorama as a cube with a full mip chain, kept between loads: the specular and
    // irradiance passes read the mip that matches each sample's footprint.
    wgpu::Texture mSource;
    wgpu::TextureView mSourceView;
    double mLastBuildMilliseconds = 0.0;
    std::shared_ptr<const image::HdrImage> mPanorama;
};

}  // namespace encore::render
