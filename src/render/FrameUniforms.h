#pragma once

// Group 0: the per-frame uniform buffer (struct Frame in frame.wgsl) and the bind group that
// binds it with the scene's lighting (SceneLighting). The camera changes through writeBuffer;
// the bind group, and so any recorded bundle, stays valid.

#include <webgpu/webgpu_cpp.h>

#include <span>

#include "encore/render/Camera.h"
#include "render/BindGroupLayouts.h"
#include "render/Lighting.h"

namespace encore::render {

struct FrameUniform {
    float projection[16];
    float view[16];
    float cameraPosition[3];
    float time;
    float viewRect[4];  // The view's part of the target in texture coordinates: x, y, w, h.
};
static_assert(sizeof(FrameUniform) == 160);

// The frame uniform of `camera` as view `view` of `viewCount` side by side (what the frame's
// group 0 holds while that view is drawn).
FrameUniform frameUniformOf(const Camera& camera,
                            float timeSeconds,
                            std::size_t view = 0,
                            std::size_t viewCount = 1);

class FrameUniforms {
  public:
    FrameUniforms() = default;
    FrameUniforms(const wgpu::Device& device,
                  const BindGroupLayouts& layouts,
                  const SceneLighting& lighting);

    // Creates the bind group again over `lighting`'s current buffers (after its light buffer
    // grew); bundles recorded with the old one must be recorded again.
    void bindLighting(const wgpu::Device& device,
                      const BindGroupLayouts& layouts,
                      const SceneLighting& lighting);
    // Binds `background` (binding 5: the transmission pass's copy of the scene behind
    // transmissive surfaces) and creates the bind group again, as bindLighting does. Null: the
    // environment atlas of binding 3 stands in (no shader without transmissive materials reads
    // it, and a texture the group already binds adds nothing for Dawn to track per pass and
    // submit). Called before a scene's strategy records anything.
    void bindTransmission(const wgpu::Device& device,
                          const BindGroupLayouts& layouts,
                          const SceneLighting& lighting,
                          wgpu::TextureView background);

    void update(const wgpu::Queue& queue, const Camera& camera, float timeSeconds) const;

    // Several views from the same recorded commands: each view's camera goes into a slot of a
    // staging buffer, and selectView() copies one slot into the frame buffer between passes,
    // so the bind group (and any bundle that set it) never changes.
    void writeViews(const wgpu::Device& device,
                    const wgpu::Queue& queue,
                    std::span<const Camera> cameras,
                    float timeSeconds);
    void selectView(const wgpu::CommandEncoder& commands, std::size_t view) const;
    const wgpu::BindGroup& bindGroup() const { return mBindGroup; }
    const wgpu::Buffer& buffer() const { return mBuffer; }

  private:
    static constexpr std::uint64_t kViewStride =
        256;  // Copy offsets need 4; 256 keeps slots apart.
    wgpu::Buffer mBuffer;
    wgpu::Buffer mViews;
    wgpu::BindGroup mBindGroup;
    wgpu::TextureView mTransmission;  // Binding 5 (transmission.wgsl), or null.
};

}  // namespace encore::render
