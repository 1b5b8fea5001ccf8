#include "trace/RayQueries.h"

#include <cstring>

#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Readback.h"
#include "gpu/Upload.h"

namespace encore::trace {
namespace {

constexpr std::uint32_t kWorkgroupSize = 64;  // trace_rays.wgsl's.

// As trace_rays.wgsl's QueryRay.
struct QueryRay {
    glm::vec3 origin{0.0f};
    float tMin = 0.0f;
    glm::vec3 direction{0.0f};
    float tMax = 0.0f;
};
static_assert(sizeof(QueryRay) == 32);

}  // namespace

Result<RayQueries> RayQueries::create(const wgpu::Device& device, shaders::ShaderLibrary& shaders) {
    RayQueries queries;
    queries.mSceneLayout = TraceSceneBuffers::layout(device);
    const wgpu::ShaderStage stage = wgpu::ShaderStage::Compute;
    queries.mRaysLayout = gpu::makeBindGroupLayout(
        device, {gpu::LayoutEntry::readOnlyStorage(0, stage), gpu::LayoutEntry::storage(1, stage)},
        "ray queries");
    ENCORE_TRY_ASSIGN(auto module, shaders.module("trace_rays.wgsl"));
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.label = "ray queries";
    descriptor.layout =
        gpu::makePipelineLayout(device, {queries.mRaysLayout, queries.mSceneLayout}, "ray queries");
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = "closestHits";
    queries.mPipeline = device.CreateComputePipeline(&descriptor);
    return queries;
}

Result<std::vector<GpuRayHit>> RayQueries::closestHits(gpu::Context& context,
                                                       const TraceSceneBuffers& scene,
                                                       std::span<const Ray> rays) const {
    if (rays.empty()) {
        return std::vector<GpuRayHit>();
    }
    const wgpu::Device& device = context.device();
    std::vector<QueryRay> queries(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        queries[i] = {rays[i].origin, rays[i].tMin, rays[i].direction, rays[i].tMax};
    }
    const wgpu::Buffer input = gpu::createStorageBuffer(device, queries, "ray queries: rays");
    const std::uint64_t hitBytes = rays.size() * sizeof(GpuRayHit);
    const wgpu::Buffer output =
        gpu::createBuffer(device, wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopySrc, hitBytes,
                          "ray queries: hits");
    const wgpu::BindGroup group =
        gpu::makeBindGroup(device, mRaysLayout, {{0, input}, {1, output}}, "ray queries");

    const wgpu::CommandEncoder encoder = device.CreateCommandEncoder();
    const wgpu::ComputePassEncoder pass = encoder.BeginComputePass();
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, group);
    pass.SetBindGroup(1, scene.bindGroup());
    pass.DispatchWorkgroups(std::uint32_t((rays.size() + kWorkgroupSize - 1) / kWorkgroupSize));
    pass.End();
    const wgpu::CommandBuffer commands = encoder.Finish();
    context.queue().Submit(1, &commands);

    ENCORE_TRY_ASSIGN(auto bytes, gpu::readBuffer(context, output, 0, hitBytes));
    std::vector<GpuRayHit> hits(rays.size());
    std::memcpy(hits.data(), bytes.data(), hitBytes);
    return hits;
}

}  // namespace encore::trace
