#include "trace/TraceSceneBuffers.h"

#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"

namespace encore::trace {

wgpu::BindGroupLayout TraceSceneBuffers::layout(const wgpu::Device& device) {
    const wgpu::ShaderStage stage = wgpu::ShaderStage::Compute;
    return gpu::makeBindGroupLayout(
        device,
        {gpu::LayoutEntry::readOnlyStorage(0, stage), gpu::LayoutEntry::readOnlyStorage(1, stage),
         gpu::LayoutEntry::readOnlyStorage(2, stage), gpu::LayoutEntry::readOnlyStorage(3, stage)},
        "trace scene");
}

TraceSceneBuffers TraceSceneBuffers::upload(const wgpu::Device& device,
                                            const wgpu::BindGroupLayout& layout,
                                            const TraceScene& scene) {
    // An empty array is bound as one zeroed element: for the objects' tree that is the node that
    // trace_bvh.wgsl reads as "no objects".
    TraceSceneBuffers buffers;
    buffers.mMeshNodes = gpu::createStorageBuffer(device, scene.meshNodes, "trace: mesh nodes");
    buffers.mTriangles = gpu::createStorageBuffer(device, scene.triangles, "trace: triangles");
    buffers.mObjectNodes =
        gpu::createStorageBuffer(device, scene.objectNodes, "trace: object nodes");
    buffers.mObjects = gpu::createStorageBuffer(device, scene.objects, "trace: objects");
    buffers.mBindGroup = gpu::makeBindGroup(device, layout,
                                            {{0, buffers.mMeshNodes},
                                             {1, buffers.mTriangles},
                                             {2, buffers.mObjectNodes},
                                             {3, buffers.mObjects}},
                                            "trace scene");
    buffers.mBytes = scene.bytes();
    return buffers;
}

}  // namespace encore::trace
