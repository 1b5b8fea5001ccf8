#pragma once

// The adapters of a new WebGPU instance, as listAdapters() (encore/gpu/Context.h) lists them:
// Dawn's native EnumerateAdapters, which returns every adapter in the order of its preference,
// where the WebGPU API's RequestAdapter hands out only the first.

#include <webgpu/webgpu_cpp.h>

#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"

namespace encore::gpu {

struct EnumeratedAdapters {
    wgpu::Instance instance;  // The adapters' instance: the one to wait on for their futures.
    std::vector<wgpu::Adapter> adapters;
    std::vector<AdapterDescription> descriptions;  // One per adapter, indexed alike.
};

// Creates an instance (with TimedWaitAny) and lists its Vulkan adapters, or with
// `allowNullBackend` Dawn's Null adapter when there is no Vulkan one. NoAdapter when none.
// `allowUnsafeApis`: the adapters are requested with Dawn's allow_unsafe_apis toggle, without
// which they do not report the features behind it (AtomicVec2uMinMax).
Result<EnumeratedAdapters> enumerateAdapters(bool allowNullBackend, bool allowUnsafeApis = false);

}  // namespace encore::gpu
