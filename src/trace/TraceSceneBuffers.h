#pragma once

// A TraceScene on the GPU: its four arrays in storage buffers and the bind group through which
// trace_bvh.wgsl reads them (its group 1), for any compute stage that traces rays.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>

#include "trace/TraceScene.h"

namespace encore::trace {

class TraceSceneBuffers {
  public:
    // The layout every shader that includes trace_bvh.wgsl declares as its group 1.
    static wgpu::BindGroupLayout layout(const wgpu::Device& device);

    static TraceSceneBuffers upload(const wgpu::Device& device,
                                    const wgpu::BindGroupLayout& layout,
                                    const TraceScene& scene);

    const wgpu::BindGroup& bindGroup() const { return mBindGroup; }
    std::uint64_t bytes() const { return mBytes; }

  private:
    wgpu::Buffer mMeshNodes;
    wgpu::Buffer mTriangles;
    wgpu::Buffer mObjectNodes;
    wgpu::Buffer mObjects;
    wgpu::BindGroup mBindGroup;
    std::uint64_t mBytes = 0;
};

}  // namespace encore::trace
