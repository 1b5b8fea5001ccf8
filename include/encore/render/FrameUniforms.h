#pragma once

// Group 0: the per-frame uniform buffer (struct Frame in frame.wgsl) and its bind group. The
// camera changes through writeBuffer; the bind group, and so any recorded bundle, stays valid.

#include <webgpu/webgpu_cpp.h>

#include "encore/render/BindGroupLayouts.h"
#include "encore/render/Camera.h"

namespace encore::render {

struct FrameUniform {
    float projection[16];
    float view[16];
    float cameraPosition[3];
    float time;
};
static_assert(sizeof(FrameUniform) == 144);

class FrameUniforms {
  public:
    FrameUniforms() = default;
    FrameUniforms(const wgpu::Device& device, const BindGroupLayouts& layouts);

    void update(const wgpu::Queue& queue, const Camera& camera, float timeSeconds) const;
    const wgpu::BindGroup& bindGroup() const { return mBindGroup; }
    const wgpu::Buffer& buffer() const { return mBuffer; }

  private:
    wgpu::Buffer mBuffer;
    wgpu::BindGroup mBindGroup;
};

}  // namespace encore::render
