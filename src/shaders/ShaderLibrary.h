#pragma once

// Shader variants and their compiled modules. A variant is derived from the primitive and
// material in one place (render/ShaderVariants) into a ShaderVariantKey; the library composes
// mesh.wgsl with the key's flags and caches one wgpu::ShaderModule per distinct key.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <set>
#include <string>
#include <unordered_map>

#include "encore/core/Result.h"

namespace encore::shaders {

// Where the vertex shader finds an instance's transform.
enum class InstanceSource : std::uint8_t {
    NodeUniform,      // One uniform buffer and bind group per node (naive .. pipeline-cache).
    InstanceStorage,  // One storage buffer of all transforms, indexed by instance_index.
    VisibleList,      // GPU culling: instance_index indexes the draw's visible-instance list.
};

// Small, padded, hashable: used as a cache key and as part of PipelineKey.
struct ShaderVariantKey {
    InstanceSource instanceSource = InstanceSource::NodeUniform;
    bool materials = false;  // glTF materials, physically based (mesh.wgsl's MATERIALS).
    bool hasTexcoord = false;
    bool hasColor = false;
    bool alphaMask = false;
    bool hasTexcoord1 = false;  // A texture of the material reads TEXCOORD_1.
    bool hasTangent = false;    // TANGENT is bound (the material has a normal map).
    // The material binds at least one texture (MATERIAL_TEXTURES). Texture-less materials bind
    // only their uniform: no texture for WebGPU to track, nothing to sample per pixel.
    bool materialTextures = false;
    // Animation (group 3 with materials, 2 without; see render/AnimationBuffers.h). SKINNED:
    // JOINTS_0/WEIGHTS_0 are bound and skinned instances use joint matrices instead of their
    // world matrix; SKINNED_8 adds JOINTS_1/WEIGHTS_1. MORPHED: the primitive has morph
    // targets, whose deltas and weights come from storage buffers.
    bool skinned = false;
    bool skinned8 = false;
    bool morphed = false;
    // The material uses iridescence, anisotropy, transmission (and volume, dispersion) or
    // diffuse transmission:
    // MATERIAL_EXTENSIONS compiles their shading. Without it the code is left out, so frames
    // of materials without them pay nothing for it (registers, occupancy: measured on the H100).
    bool materialExtensions = false;
    // The material's textures sample through more than one palette entry (SAMPLER_PALETTE);
    // without it every slot samples with materialSampler0.
    bool samplerPalette = false;
    // With materials: 0, or the four pass targets beside the colour (PASS_TARGETS, encore
    // batch's passes in one render pass, render/PassTargets.h), their segmentation ids counting
    // 1 nodes, 2 meshes, 3 materials.
    std::uint8_t passTargets = 0;
    std::uint8_t padding[2] = {};  // Keeps the key free of implicit padding (hashed bytewise).

    bool animated() const { return skinned || morphed; }

    bool operator==(const ShaderVariantKey&) const = default;
    std::set<std::string, std::less<>> flags() const;
    std::string describe() const;  // e.g. "INSTANCE_STORAGE MATERIALS HAS_TEXCOORD"
};

struct ShaderVariantKeyHash {
    std::size_t operator()(const ShaderVariantKey& key) const noexcept;
};

class ShaderLibrary {
  public:
    explicit ShaderLibrary(wgpu::Device device) : mDevice(std::move(device)) {}

    // The module of mesh.wgsl for this variant, compiled on first use.
    Result<wgpu::ShaderModule> meshModule(const ShaderVariantKey& key);

    // Any embedded .wgsl file composed with the given flags (compute shaders and helpers).
    Result<wgpu::ShaderModule> module(const std::string& fileName,
                                      const std::set<std::string, std::less<>>& flags = {});

    std::size_t moduleCount() const { return mMeshModules.size() + mOtherModules.size(); }

  private:
    wgpu::Device mDevice;
    std::unordered_map<ShaderVariantKey, wgpu::ShaderModule, ShaderVariantKeyHash> mMeshModules;
    std::unordered_map<std::string, wgpu::ShaderModule> mOtherModules;
};

}  // namespace encore::shaders
