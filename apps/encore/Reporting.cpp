#include <cstdio>
#include <cstdlib>

#include "Commands.h"
#include "DeviceOptions.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::app {

int reportError(const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.message.c_str());
    switch (error.code) {
        case ErrorCode::NoAdapter:
            return kExitNoAdapter;
        case ErrorCode::ValidationError:
        case ErrorCode::DeviceError:
            return kExitGpuError;
        case ErrorCode::OutOfMemory:
            return kExitOutOfMemory;
        case ErrorCode::InvalidArgument:
            return kExitUsage;
        case ErrorCode::NoDisplay:
            return kExitNoDisplay;
        default:
            return kExitFailure;
    }
}

Result<scene::SceneData> loadModel(const std::string& path,
                                   scene::LoadOptions options,
                                   const GlobalOptions& global) {
    options.allowUrisOutside = global.allowUrisOutside;
    auto scene = scene::loadScene(path, options);
    if (scene) {
        for (const auto& warning : scene->warnings) {
            std::fprintf(stderr, "warning: %s\n", warning.c_str());
        }
    }
    return scene;
}

void injectFaultsForTests(gpu::Context& context) {
    if (std::getenv("ENCORE_TEST_FORCE_DEVICE_LOSS")) {
        context.device().ForceLoss(wgpu::DeviceLostReason::Unknown,
                                   "forced by ENCORE_TEST_FORCE_DEVICE_LOSS");
    }
    if (std::getenv("ENCORE_TEST_INJECT_OUT_OF_MEMORY")) {
        context.device().InjectError(wgpu::ErrorType::OutOfMemory,
                                     "injected by ENCORE_TEST_INJECT_OUT_OF_MEMORY");
    }
}

Result<std::size_t> chosenDevice(const GlobalOptions& global) {
    if (global.device) {
        return *global.device;
    }
    const char* variable = std::getenv("ENCORE_DEVICE");
    if (!variable || !*variable) {
        return std::size_t{0};
    }
    ENCORE_TRY_ASSIGN(auto index, parseDeviceIndex(variable));
    return index;
}

Result<gpu::Context> createContext(const GlobalOptions& global,
                                   bool timestamps,
                                   std::optional<std::size_t> device) {
    gpu::ContextOptions options;
    if (device) {
        options.adapterIndex = *device;
    } else {
        ENCORE_TRY_ASSIGN(options.adapterIndex, chosenDevice(global));
    }
    options.allowNullBackend = global.allowNullBackend;
    options.timestamps = timestamps;
    render::requestVisibilityFeatures(options);
    auto context = gpu::Context::create(options);
    if (context && global.verbose) {
        std::fprintf(stderr, "adapter: %s\n", context->adapterDescription().summary().c_str());
    }
    return context;
}

}  // namespace encore::app
