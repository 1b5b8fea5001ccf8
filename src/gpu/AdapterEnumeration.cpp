#include "gpu/AdapterEnumeration.h"

#include <dawn/native/DawnNative.h>

#include <string>
#include <string_view>

namespace encore::gpu {
namespace {

std::string toString(wgpu::StringView view) {
    return std::string(std::string_view(view));
}

AdapterDescription describe(const wgpu::Adapter& adapter, std::size_t index) {
    wgpu::AdapterInfo info;
    adapter.GetInfo(&info);
    AdapterDescription description;
    description.index = index;
    description.name = toString(info.device);
    description.vendor = toString(info.vendor);
    description.architecture = toString(info.architecture);
    description.driver = toString(info.description);
    description.backend = info.backendType;
    description.adapterType = info.adapterType;
    return description;
}

}  // namespace

Result<EnumeratedAdapters> enumerateAdapters(bool allowNullBackend, bool allowUnsafeApis) {
    static constexpr auto kTimedWaitAny = wgpu::InstanceFeatureName::TimedWaitAny;
    wgpu::InstanceDescriptor instanceDescriptor{};
    instanceDescriptor.requiredFeatureCount = 1;
    instanceDescriptor.requiredFeatures = &kTimedWaitAny;
    // The native instance lists every adapter; the wgpu::Instance taken from it holds its own
    // reference, so the instance and its adapters outlive `native`.
    const dawn::native::Instance native(&instanceDescriptor);
    EnumeratedAdapters result;
    result.instance = wgpu::Instance(native.Get());
    if (!result.instance) {
        return makeError(ErrorCode::NoAdapter, "Dawn could not create a WebGPU instance.");
    }

    // Vulkan only: it is the backend Encore is written and tested for. The order is Dawn's, as
    // RequestAdapter with the same options would choose, so adapter 0 is its choice.
    wgpu::RequestAdapterOptions options{};
    options.powerPreference = wgpu::PowerPreference::HighPerformance;
    options.backendType = wgpu::BackendType::Vulkan;
    static constexpr const char* kUnsafeApis[] = {"allow_unsafe_apis"};
    wgpu::DawnTogglesDescriptor toggles;
    if (allowUnsafeApis) {
        toggles.enabledToggleCount = 1;
        toggles.enabledToggles = kUnsafeApis;
        options.nextInChain = &toggles;
    }
    std::vector<dawn::native::Adapter> found = native.EnumerateAdapters(&options);
    if (found.empty() && allowNullBackend) {
        options.backendType = wgpu::BackendType::Null;
        found = native.EnumerateAdapters(&options);
    }
    for (const dawn::native::Adapter& adapter : found) {
        result.adapters.emplace_back(adapter.Get());
        result.descriptions.push_back(describe(result.adapters.back(), result.adapters.size() - 1));
    }
    if (result.adapters.empty()) {
        return makeError(
            ErrorCode::NoAdapter,
            allowNullBackend
                ? "no adapter found (Dawn offered neither a Vulkan adapter nor its Null backend)."
                : "no Vulkan adapter found (Dawn offered only its Null backend, which renders "
                  "nothing; install a Vulkan driver such as Mesa >= 25 lavapipe, or pass "
                  "--allow-null-backend for a validation-only run).");
    }
    return result;
}

}  // namespace encore::gpu
