#pragma once

// The bind group layouts shared by every strategy, ordered by how often a group changes:
//   0  frame      camera matrices (uniform), then the scene's lighting: lighting uniform,
//                 punctual lights (storage), specular and irradiance cubes, BRDF lookup table
//                 and their sampler; once per pass or bundle
//   1  instances  one node's transform (uniform), all transforms (read-only storage), or all
//                 transforms plus a draw's visible-instance list (GPU culling)
//   2  material   material uniform, its samplers and a texture per texture slot; materials
//                 without the extensions' shading bind only the base slots (materialBase),
//                 materials without any texture the uniform alone (materialUniformOnly)
//   3  animation  skinned or morphed primitives only (AnimationBuffers): a draw's animation
//                 record (uniform, dynamic offset), joint matrices, morph weights, morph deltas
//                 and per-instance joint/weight offsets (read-only storage). Strategies without
//                 materials have no group 2 and bind it as group 2 (animationGroupIndex).

#include <webgpu/webgpu_cpp.h>

namespace encore::render {

// std140-style layout of one instance's transforms in WGSL (struct Transform in mesh.wgsl).
struct TransformUniform {
    float world[16];
    float normal[16];
};
static_assert(sizeof(TransformUniform) == 128);

struct BindGroupLayouts {
    wgpu::BindGroupLayout frame;
    wgpu::BindGroupLayout nodeUniform;
    wgpu::BindGroupLayout instanceStorage;
    // GPU culling: all transforms plus one draw's visible list (dynamic offset).
    wgpu::BindGroupLayout culledInstances;
    wgpu::BindGroupLayout material;
    // mesh.wgsl's MATERIAL_TEXTURES without MATERIAL_EXTENSIONS: the slots before the
    // extensions' (fewer textures for Dawn to track in every pass that draws them).
    wgpu::BindGroupLayout materialBase;
    wgpu::BindGroupLayout materialUniformOnly;  // mesh.wgsl without MATERIAL_TEXTURES.
    wgpu::BindGroupLayout animation;            // mesh.wgsl's ANIMATED variants.

    static BindGroupLayouts create(const wgpu::Device& device);
};

}  // namespace encore::render
