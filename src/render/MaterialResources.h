#pragma once

// MaterialResources owns the GPU side of a scene's materials: textures, samplers, one uniform
// buffer holding every material's factors, and one bind group per material for group 2 of
// mesh.wgsl (BindGroupLayouts::material, material.wgsl).
//
// A material has twelve texture slots (TextureSlot, one row each in the table of
// MaterialSlots.h): the core metallic-roughness, normal, occlusion and emissive textures and
// those of the extensions Encore shades. Each slot binds its own texture and has its own
// texCoord set, KHR_texture_transform and sampler palette entry in the uniform
// (MaterialUniform.h); the material binds a palette of up to four samplers (SamplerPalette.h)
// that its slots share. Textures: one
// per glTF image that a material references, in the colour space of its use (the table's: base
// colour, emissive, specular colour, sheen colour and the specular-glossiness texture sRGB; the
// rest linear); an image used both ways gets two textures. Every texture has its full mip
// chain, generated on the GPU at creation. A slot without a texture, or whose image is missing
// or undecoded, binds a 1x1 opaque white texture, so factors multiply through unchanged and the
// shader needs no variant for it (normal maps are switched by a flag).
//
// Samplers: one per distinct glTF sampler state (equal states share one), and the glTF default
// (repeat, linear, linear mipmaps) for materials without a texture. A sampler that glTF
// declares without mipmaps (minFilter NEAREST or LINEAR) only reads level 0. A material whose
// textures use more than four distinct states samples the later slots with the nearest of the
// first four, with a warning naming the material, the slots and the samplers.
//
// Uniforms: material i lives at i * uniformStride() in uniformBuffer(), as a MaterialUniform.
// updateMaterial rewrites that range, so factors can change after render bundles are recorded
// without re-creating any bind group.

#include <webgpu/webgpu_cpp.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"
#include "render/BindGroupLayouts.h"
#include "render/MaterialSlots.h"
#include "render/MaterialUniform.h"
#include "shaders/ShaderLibrary.h"

namespace encore::gpu {
class ResourcePool;
}

namespace encore::render {

class MipmapGenerator;
class StagedImages;

// Where create()'s time went on the CPU, in milliseconds.
struct TextureUploadTimes {
    double creation = 0.0;  // Device::CreateTexture.
    // Level 0: Queue::WriteTexture (Dawn copies the pixels into staging memory), or waiting for
    // a staged image and recording its copy.
    double writes = 0.0;
    double mipmaps = 0.0;  // Recording the mip generation.
    double submit = 0.0;   // Finishing and submitting those commands.
};

class MaterialResources {
  public:
    // Uploads what the materials of `scene` reference and records one submit that generates
    // the mip chains. An image larger than maxTextureDimension (0: the device's
    // maxTextureDimension2D) is downscaled to fit, keeping its aspect ratio, with a warning
    // naming it and both sizes (image/ImageResize.h). Fails, naming the image, when its pixel
    // data does not match its size, and when a material names a texture, or a texture a
    // sampler, that does not exist. `scene` need not outlive the result. WebGPU validation
    // errors surface through the device's error callback. `mipmaps` is a generator kept from
    // one scene to the next (RenderSetup::mipmaps, so its pipelines are created once); null:
    // one made for this call. `staged`: the scene's images already in staging buffers
    // (StagedImages.h), copied from there rather than written through the queue. `pool`: where
    // the textures and the uniform buffer come from (gpu/ResourcePool.h); null: created.
    // `uploads`: the encoder the copies and mip passes are recorded into, which the caller
    // submits (one submit for a whole scene); null: recorded and submitted here.
    static Result<MaterialResources> create(const wgpu::Device& device,
                                            const wgpu::Queue& queue,
                                            shaders::ShaderLibrary& shaders,
                                            const BindGroupLayouts& layouts,
                                            const scene::SceneData& scene,
                                            const SampledTextures& sampled = {},
                                            std::uint32_t maxTextureDimension = 0,
                                            MipmapGenerator* mipmaps = nullptr,
                                            StagedImages* staged = nullptr,
                                            gpu::ResourcePool* pool = nullptr,
                                            wgpu::CommandEncoder uploads = nullptr);

    // Hands the textures and the uniform buffer to `pool` (the scene is being released: no
    // bind group of this object is used again).
    void giveBackTo(gpu::ResourcePool& pool);

    MaterialResources(MaterialResources&&) noexcept = default;
    MaterialResources& operator=(MaterialResources&&) noexcept = default;
    MaterialResources(const MaterialResources&) = delete;
    MaterialResources& operator=(const MaterialResources&) = delete;

    // The group 2 bind group of a material for pipelines compiled with every extension
    // (MATERIAL_EXTENSIONS, whatever the material uses); `material` must be a
    // valid index of the scene. Its layout is BindGroupLayouts::material when
    // textured(material), else BindGroupLayouts::materialUniformOnly.
    const wgpu::BindGroup& bindGroup(scene::MaterialId material) const;
    // The group 2 bind group for the material's own pipelines, whose ShaderVariantKey follows
    // the material (materialShadesExtensions): without the extensions' shading, a textured
    // material binds only the base slots (BindGroupLayouts::materialBase); otherwise the same
    // group as bindGroup.
    const wgpu::BindGroup& drawBindGroup(scene::MaterialId material) const;
    // Whether the material binds a texture in any slot (an image that was uploaded); pipelines
    // drawing it need the MATERIAL_TEXTURES variant. Changes only through
    // replaceBaseColorImage.
    bool textured(scene::MaterialId material) const;
    // Whether the material's shading needs the MATERIAL_EXTENSIONS variant
    // (materialShadesExtensions): drawBindGroup binds the whole group then, else the base slots.
    bool shadesExtensions(scene::MaterialId material) const;
    // Whether a slot of the material samples through a palette entry other than the first
    // (pipelines drawing it need the SAMPLER_PALETTE variant).
    bool samplesThroughPalette(scene::MaterialId material) const;

    // Rewrites the uniform range of `material` from `values` (factors, texture transform,
    // alpha cutoff). Textures and samplers stay as created: changing which texture a material
    // uses needs a new MaterialResources.
    void updateMaterial(const wgpu::Queue& queue,
                        scene::MaterialId material,
                        const scene::Material& values);

    // Replaces the base colour image of `material` with `image` (uploaded as a new sRGB texture
    // with its mip chain), rebuilds the material's bind group and destroys the texture it
    // replaced unless another material or the default still uses it. Bumps generation(): render
    // bundles that bound the old bind group must be re-recorded before they execute again. A
    // material without textures becomes textured (callers choose its pipelines again).
    Result<void> replaceBaseColorImage(const wgpu::Device& device,
                                       const wgpu::Queue& queue,
                                       shaders::ShaderLibrary& shaders,
                                       const BindGroupLayouts& layouts,
                                       scene::MaterialId material,
                                       const scene::Image& image);

    // Where create()'s time went.
    const TextureUploadTimes& uploadTimes() const { return mUploadTimes; }

    // Pixels written into the textures' first level since create() (the default texture and
    // replaced images included; mip levels are generated on the GPU and not counted).
    std::uint64_t uploadedBytes() const { return mUploadedBytes; }
    // Incremented whenever a bind group is replaced.
    std::uint64_t generation() const { return mGeneration; }
    // Incremented whenever a material's uniform range is rewritten (updateMaterial,
    // replaceBaseColorImage): copies of the uniforms made before are stale.
    std::uint64_t uniformGeneration() const { return mUniformGeneration; }

    // For each material, the first material whose bind group binds the same textures and
    // samplers under the same variants (textured, shadesExtensions): one bind group then
    // serves both, given each one's uniform from elsewhere (the visibility strategy's shading
    // bins, MaterialBins.h). Untextured materials bind their uniform alone: those of one
    // variant all share.
    std::vector<std::uint32_t> sharedBindingLeaders() const;

    std::size_t materialCount() const { return mBindGroups.size(); }
    // GPU textures created, the default one included.
    std::size_t textureCount() const { return mTextures.size(); }
    // wgpu::Samplers created, the default one included.
    std::size_t samplerCount() const { return mSamplers.size(); }

    // For statistics and tests: the texture made of `image` for `space`, or nullptr when none
    // was made (the image is unreferenced in that space, missing or undecoded).
    const wgpu::Texture* texture(scene::ImageId image, ColorSpace space) const;
    const wgpu::Texture& defaultBaseColorTexture() const { return mTextures[kDefaultTexture]; }
    // The sampler shared by every scene sampler with the state of `sampler`.
    const wgpu::Sampler& sampler(scene::SamplerId sampler) const;
    // True when the material binds the default white texture instead of an image.
    bool usesDefaultBaseColor(scene::MaterialId material) const;

    // The buffer behind every material's binding 0 (Uniform | CopyDst | CopySrc usage).
    const wgpu::Buffer& uniformBuffer() const { return mUniforms; }
    std::uint64_t uniformStride() const { return mUniformStride; }

  private:
    static constexpr std::size_t kDefaultTexture = 0;
    static constexpr std::size_t kNone = SIZE_MAX;

    // Indices into mTextures of the textures made of one image.
    struct ImageTextures {
        std::size_t srgb = kNone;
        std::size_t linear = kNone;
    };
    struct Builder;

    MaterialResources() = default;

    std::vector<wgpu::Texture> mTextures;       // [kDefaultTexture] is the white default.
    std::vector<ImageTextures> mImageTextures;  // Indexed by ImageId.
    std::vector<wgpu::Sampler> mSamplers;
    std::vector<std::size_t> mSceneSamplers;  // SamplerId -> index into mSamplers.
    wgpu::Buffer mUniforms;
    std::uint64_t mUniformStride = 256;
    std::vector<wgpu::BindGroup> mBindGroups;  // Indexed by MaterialId.
    // Indexed by MaterialId: the base-slot group of a textured material without the
    // extensions' shading, else null (drawBindGroup returns mBindGroups').
    std::vector<wgpu::BindGroup> mBaseBindGroups;
    std::vector<bool> mShadesExtensions;  // MaterialId -> materialShadesExtensions.
    using SlotIndices = std::array<std::size_t, kMaterialTextureSlotCount>;
    std::vector<SlotIndices> mMaterialTextures;  // MaterialId -> slot -> index into mTextures.
    // MaterialId -> palette entry -> index into mSamplers (unused entries repeat the first).
    std::vector<std::array<std::size_t, kMaterialSamplerCount>> mMaterialPalettes;
    std::vector<SlotSamplerEntries> mMaterialSamplerEntries;  // MaterialId -> slot -> entry.
    std::vector<bool> mTextured;                              // MaterialId -> binds a texture.
    std::uint64_t mGeneration = 0;
    std::uint64_t mUniformGeneration = 0;
    std::uint64_t mUploadedBytes = 0;
    TextureUploadTimes mUploadTimes;

    // Bits of the slots that bind an uploaded texture (MaterialUniform::flags[3]).
    std::uint32_t texturedSlots(std::size_t material) const;
    // The material's group with every slot (`baseSlots` false) or the base slots only.
    wgpu::BindGroup createBindGroup(const wgpu::Device& device,
                                    const BindGroupLayouts& layouts,
                                    std::size_t material,
                                    const char* label,
                                    bool baseSlots = false) const;
    // Creates or replaces both bind groups of `material` (mBindGroups, mBaseBindGroups).
    void createBindGroups(const wgpu::Device& device,
                          const BindGroupLayouts& layouts,
                          std::size_t material,
                          const char* label);
};

}  // namespace encore::render
