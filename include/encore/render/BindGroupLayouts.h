#pragma once

// The bind group layouts shared by every strategy, ordered by how often a group changes:
//   0  frame      camera matrices (uniform), once per pass or bundle
//   1  instances  either one node's transform (uniform) or all transforms (read-only storage)
//   2  material   material uniform, base colour sampler and texture

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
    wgpu::BindGroupLayout material;

    static BindGroupLayouts create(const wgpu::Device& device);
};

}  // namespace encore::render
