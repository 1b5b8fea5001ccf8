#include "gpu/CreationCounts.h"

#include <webgpu/webgpu.h>

#include <cstdio>
#include <cstdlib>
#include <string_view>

// The linker renames Encore's calls to the three functions to __wrap_NAME and the originals to
// __real_NAME (src/gpu/CMakeLists.txt).
extern "C" {
WGPUBuffer __real_wgpuDeviceCreateBuffer(WGPUDevice device, const WGPUBufferDescriptor* descriptor);
WGPUTexture __real_wgpuDeviceCreateTexture(WGPUDevice device,
                                           const WGPUTextureDescriptor* descriptor);
WGPUQuerySet __real_wgpuDeviceCreateQuerySet(WGPUDevice device,
                                             const WGPUQuerySetDescriptor* descriptor);
}

namespace encore::gpu {
namespace {

thread_local CreationCounts tCounts;

bool tracing() {
    static const bool trace = [] {
        const char* value = std::getenv("ENCORE_TRACE_GPU_CREATION");
        return value && *value && std::string_view(value) != "0";
    }();
    return trace;
}

void trace(const char* kind, WGPUStringView label, std::uint64_t bytes) {
    const std::string_view name =
        label.data ? std::string_view(label.data, label.length == WGPU_STRLEN
                                                      ? std::string_view(label.data).size()
                                                      : label.length)
                   : std::string_view();
    std::fprintf(stderr, "gpu-create %s '%.*s' %llu\n", kind, int(name.size()), name.data(),
                 static_cast<unsigned long long>(bytes));
}

}  // namespace

CreationCounts threadCreationCounts() {
    return tCounts;
}

}  // namespace encore::gpu

extern "C" {

WGPUBuffer __wrap_wgpuDeviceCreateBuffer(WGPUDevice device,
                                         const WGPUBufferDescriptor* descriptor) {
    using encore::gpu::tCounts;
    ++tCounts.buffers;
    if (descriptor) {
        const bool mappable =
            descriptor->mappedAtCreation ||
            (descriptor->usage & (WGPUBufferUsage_MapRead | WGPUBufferUsage_MapWrite)) != 0;
        if (mappable) {
            tCounts.bytesMapped += descriptor->size;
        }
        if (encore::gpu::tracing()) {
            encore::gpu::trace(mappable ? "mapped-buffer" : "buffer", descriptor->label,
                               descriptor->size);
        }
    }
    return __real_wgpuDeviceCreateBuffer(device, descriptor);
}

WGPUTexture __wrap_wgpuDeviceCreateTexture(WGPUDevice device,
                                           const WGPUTextureDescriptor* descriptor) {
    ++encore::gpu::tCounts.textures;
    if (descriptor && encore::gpu::tracing()) {
        encore::gpu::trace("texture", descriptor->label,
                           std::uint64_t(descriptor->size.width) * descriptor->size.height *
                               descriptor->size.depthOrArrayLayers);
    }
    return __real_wgpuDeviceCreateTexture(device, descriptor);
}

WGPUQuerySet __wrap_wgpuDeviceCreateQuerySet(WGPUDevice device,
                                             const WGPUQuerySetDescriptor* descriptor) {
    ++encore::gpu::tCounts.querySets;
    if (descriptor && encore::gpu::tracing()) {
        encore::gpu::trace("query-set", descriptor->label, descriptor->count);
    }
    return __real_wgpuDeviceCreateQuerySet(device, descriptor);
}
}
