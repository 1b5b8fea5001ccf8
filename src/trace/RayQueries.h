#pragma once

// Closest hits of many rays at once on the GPU (trace_rays.wgsl): what tests compare with the
// CPU's trace::closestHit, and a way for tools to pick what lies under a pixel.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "shaders/ShaderLibrary.h"
#include "trace/RayCast.h"
#include "trace/TraceSceneBuffers.h"

namespace encore::trace {

// As trace_bvh.wgsl's TraceHit: object kNoObject when the ray hit nothing.
struct GpuRayHit {
    float t = 0.0f;
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
    std::uint32_t padding = 0;  // WGSL aligns the vec2f to 8 bytes.
    glm::vec2 barycentric{0.0f};

    static constexpr std::uint32_t kNoObject = 0xffffffffu;
    bool hit() const { return object != kNoObject; }
};
static_assert(sizeof(GpuRayHit) == 24);

class RayQueries {
  public:
    static Result<RayQueries> create(const wgpu::Device& device, shaders::ShaderLibrary& shaders);

    const wgpu::BindGroupLayout& sceneLayout() const { return mSceneLayout; }

    // Traces the rays and waits for their hits, in the rays' order.
    Result<std::vector<GpuRayHit>> closestHits(gpu::Context& context,
                                               const TraceSceneBuffers& scene,
                                               std::span<const Ray> rays) const;

  private:
    wgpu::BindGroupLayout mSceneLayout;
    wgpu::BindGroupLayout mRaysLayout;
    wgpu::ComputePipeline mPipeline;
};

}  // namespace encore::trace
