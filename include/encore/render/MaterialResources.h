#pragma once

// MaterialResources owns the GPU side of a scene's materials: textures, samplers, one uniform
// buffer holding every material's factors, and one bind group per material for group 2 of
// mesh.wgsl (BindGroupLayouts::material).
//
// Textures: one per glTF image that a material references, in the colour space of its use.
// Images used as base colour or emissive textures are RGBA8UnormSrgb, images used as
// metallic-roughness, normal or occlusion textures RGBA8Unorm; an image used both ways gets
// two textures. Every texture has its full mip chain, generated on the GPU at creation.
// A material without a base colour texture, or whose image is missing or was not decoded
// (empty pixels), binds a 1x1 opaque white sRGB texture instead, so the shader needs no
// variant for it.
//
// Samplers: one per distinct glTF sampler state (equal states share one), and the glTF default
// (repeat, linear, linear mipmaps) for materials without a base colour texture. A sampler that
// glTF declares without mipmaps (minFilter NEAREST or LINEAR) only reads level 0.
//
// Uniforms: material i lives at i * uniformStride() in uniformBuffer(), as a MaterialUniform.
// updateMaterial rewrites that range, so factors can change after render bundles are recorded
// without re-creating any bind group.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/BindGroupLayouts.h"
#include "encore/scene/SceneData.h"
#include "encore/shaders/ShaderLibrary.h"

namespace encore::render {

// The `Material` struct of mesh.wgsl, byte for byte.
struct MaterialUniform {
    float baseColorFactor[4];
    // KHR_texture_transform of the base colour texture as the rows of the 2x3 matrix
    // T * R * S applied to (u, v, 1); identity when the texture has no transform.
    float texcoordRow0[4];
    float texcoordRow1[4];
    // The material's alphaCutoff for AlphaMode::Mask (0 stays 0), 0 otherwise.
    float alphaCutoff;
    // 1 for AlphaMode::Blend, whose alpha is opacity; OPAQUE and MASK write alpha 1 (glTF).
    float alphaBlend;
    float padding[2];
};
static_assert(sizeof(MaterialUniform) == 64);

// The uniform contents of `material` (no GPU involved).
MaterialUniform makeMaterialUniform(const scene::Material& material);

enum class ColorSpace : std::uint8_t {
    Srgb,    // Colour data: base colour, emissive.
    Linear,  // Non-colour data: metallic-roughness, normal, occlusion.
};

// Which material texture slots the shaders sample. Only those are uploaded (with mip chains);
// references in the others are still validated. mesh.wgsl samples the base colour alone.
struct SampledTextures {
    bool baseColor = true;
    bool metallicRoughness = false;
    bool normal = false;
    bool occlusion = false;
    bool emissive = false;

    static SampledTextures all() { return {true, true, true, true, true}; }
};

class MaterialResources {
  public:
    // Uploads what the materials of `scene` reference and records one submit that generates
    // the mip chains. Fails, naming the image, when an image exceeds the device's
    // maxTextureDimension2D or its pixel data does not match its size, and when a material
    // names a texture, or a texture a sampler, that does not exist. `scene` need not outlive
    // the result. WebGPU validation errors surface through the device's error callback.
    static Result<MaterialResources> create(const wgpu::Device& device,
                                            const wgpu::Queue& queue,
                                            shaders::ShaderLibrary& shaders,
                                            const BindGroupLayouts& layouts,
                                            const scene::SceneData& scene,
                                            const SampledTextures& sampled = {});

    MaterialResources(MaterialResources&&) noexcept = default;
    MaterialResources& operator=(MaterialResources&&) noexcept = default;
    MaterialResources(const MaterialResources&) = delete;
    MaterialResources& operator=(const MaterialResources&) = delete;

    // The group 2 bind group of a material; `material` must be a valid index of the scene.
    const wgpu::BindGroup& bindGroup(scene::MaterialId material) const;

    // Rewrites the uniform range of `material` from `values` (factors, texture transform,
    // alpha cutoff). Textures and samplers stay as created: changing which texture a material
    // uses needs a new MaterialResources.
    void updateMaterial(const wgpu::Queue& queue,
                        scene::MaterialId material,
                        const scene::Material& values);

    // Replaces the base colour image of `material` with `image` (uploaded as a new sRGB texture
    // with its mip chain), rebuilds the material's bind group and destroys the texture it
    // replaced unless another material or the default still uses it. Bumps generation(): render
    // bundles that bound the old bind group must be re-recorded before they execute again.
    Result<void> replaceBaseColorImage(const wgpu::Device& device, const wgpu::Queue& queue,
                                       shaders::ShaderLibrary& shaders,
                                       const BindGroupLayouts& layouts,
                                       scene::MaterialId material, const scene::Image& image);

    // Incremented whenever a bind group is replaced.
    std::uint64_t generation() const { return mGeneration; }

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
    std::vector<bool> mDefaultBaseColor;      // Indexed by MaterialId.
    wgpu::Buffer mUniforms;
    std::uint64_t mUniformStride = 256;
    std::vector<wgpu::BindGroup> mBindGroups;  // Indexed by MaterialId.
    std::vector<std::size_t> mMaterialTextures;  // MaterialId -> index into mTextures.
    std::vector<std::size_t> mMaterialSamplers;  // MaterialId -> index into mSamplers.
    std::uint64_t mGeneration = 0;

    wgpu::BindGroup createBindGroup(const wgpu::Device& device, const BindGroupLayouts& layouts,
                                    std::size_t material, const char* label) const;
};

}  // namespace encore::render
