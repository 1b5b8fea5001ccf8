#include "encore/gpu/Context.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <string_view>

#include "core/Log.h"
#include "gpu/AdapterEnumeration.h"
#include "gpu/OutOfMemoryScope.h"

namespace encore::gpu {

struct Context::ErrorLog {
    std::mutex mutex;
    std::vector<std::string> errors;
    std::size_t total = 0;
    bool lost = false;
    bool outOfMemory = false;  // Since the last takeErrors().

    void record(std::string message) {
        logError(message);
        std::lock_guard lock(mutex);
        ++total;
        errors.push_back(std::move(message));
    }
    static void logError(const std::string& message) { log(LogLevel::Error, message); }
};

namespace {

std::string toString(wgpu::StringView view) {
    return std::string(std::string_view(view));
}

std::string errorTypeName(wgpu::ErrorType type) {
    switch (type) {
        case wgpu::ErrorType::Validation:
            return "validation error";
        case wgpu::ErrorType::OutOfMemory:
            return "out-of-memory error";
        case wgpu::ErrorType::Internal:
            return "internal error";
        default:
            return "error";
    }
}

// ENCORE_DAWN_TOGGLES, split at commas.
std::vector<std::string> togglesFromEnvironment() {
    std::vector<std::string> toggles;
    const char* variable = std::getenv("ENCORE_DAWN_TOGGLES");
    std::string_view rest = variable ? variable : "";
    while (!rest.empty()) {
        const std::size_t comma = rest.find(',');
        if (const std::string_view name = rest.substr(0, comma); !name.empty()) {
            toggles.emplace_back(name);
        }
        rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    }
    return toggles;
}

}  // namespace

std::string backendName(wgpu::BackendType backend) {
    switch (backend) {
        case wgpu::BackendType::Null:
            return "Null";
        case wgpu::BackendType::WebGPU:
            return "WebGPU";
        case wgpu::BackendType::D3D11:
            return "D3D11";
        case wgpu::BackendType::D3D12:
            return "D3D12";
        case wgpu::BackendType::Metal:
            return "Metal";
        case wgpu::BackendType::Vulkan:
            return "Vulkan";
        case wgpu::BackendType::OpenGL:
            return "OpenGL";
        case wgpu::BackendType::OpenGLES:
            return "OpenGLES";
        default:
            return "Undefined";
    }
}

std::string adapterTypeName(wgpu::AdapterType type) {
    switch (type) {
        case wgpu::AdapterType::DiscreteGPU:
            return "discrete GPU";
        case wgpu::AdapterType::IntegratedGPU:
            return "integrated GPU";
        case wgpu::AdapterType::CPU:
            return "CPU";
        default:
            return "unknown type";
    }
}

std::string AdapterDescription::summary() const {
    std::string text = name + ", " + backendName(backend) + ", " + adapterTypeName(adapterType);
    if (!driver.empty()) {
        text += ", driver " + driver;
    }
    return text;
}

Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

Context::~Context() {
    if (mDevice) {
        // Destroying explicitly resolves the device-lost callback now, while the error log it
        // points to is still alive.
        mDevice.Destroy();
    }
}

Result<Context> Context::create(const ContextOptions& options) {
    Context context;
    context.mErrors = std::make_shared<ErrorLog>();
    context.mOptions = options;
    ENCORE_TRY(context.acquireDevice());
    return context;
}

Result<std::vector<AdapterDescription>> listAdapters(bool allowNullBackend) {
    ENCORE_TRY_ASSIGN(auto enumerated, enumerateAdapters(allowNullBackend));
    return std::move(enumerated.descriptions);
}

std::vector<std::size_t> adaptersLike(std::span<const AdapterDescription> adapters,
                                      std::size_t first) {
    std::vector<std::size_t> like;
    if (first >= adapters.size()) {
        return like;
    }
    for (const AdapterDescription& adapter : adapters) {
        if (adapter.adapterType == adapters[first].adapterType &&
            adapter.backend == adapters[first].backend) {
            like.push_back(adapter.index);
        }
    }
    return like;
}

namespace {

// The error of an adapter index past the machine's adapters, listing them.
Error noSuchAdapter(std::size_t index, const std::vector<AdapterDescription>& descriptions) {
    std::string names;
    for (const AdapterDescription& adapter : descriptions) {
        names +=
            (names.empty() ? "" : "; ") + std::to_string(adapter.index) + ": " + adapter.summary();
    }
    const std::size_t count = descriptions.size();
    return makeError(ErrorCode::NoAdapter, "there is no device " + std::to_string(index) +
                                               ": this machine has " + std::to_string(count) +
                                               " adapter" + (count == 1 ? "" : "s") + " (" + names +
                                               "); `encore info` lists them.");
}

// What a device is asked for: its features, and the Dawn toggles turned on and off (the names
// of ENCORE_DAWN_TOGGLES point into `environmentToggles`).
struct DeviceRequest {
    std::vector<wgpu::FeatureName> features;
    std::vector<std::string> environmentToggles;
    std::vector<const char*> enabledToggles;
    std::vector<const char*> disabledToggles;
};

void fillDeviceRequest(DeviceRequest& request,
                       const ContextOptions& options,
                       const wgpu::Adapter& adapter) {
    if (options.timestamps && adapter.HasFeature(wgpu::FeatureName::TimestampQuery)) {
        request.features.push_back(wgpu::FeatureName::TimestampQuery);
        request.disabledToggles.push_back("timestamp_quantization");
    }
    for (auto feature : options.optionalFeatures) {
        if (adapter.HasFeature(feature)) {
            request.features.push_back(feature);
        }
    }
    // Features behind allow_unsafe_apis need it on the device as on the adapter request.
    if (options.allowUnsafeApis) {
        request.enabledToggles.push_back("allow_unsafe_apis");
    }
    // ENCORE_DAWN_TOGGLES=name,-name,...: Dawn device toggles turned on (or off), for measuring
    // what Dawn's own work costs (e.g. skip_validation); never needed to render correctly.
    request.environmentToggles = togglesFromEnvironment();
    for (const std::string& toggle : request.environmentToggles) {
        if (toggle.starts_with('-')) {
            request.disabledToggles.push_back(toggle.c_str() + 1);
        } else {
            request.enabledToggles.push_back(toggle.c_str());
        }
    }
    if (!request.environmentToggles.empty()) {
        logWarning("Dawn toggles from ENCORE_DAWN_TOGGLES: " +
                   std::string(std::getenv("ENCORE_DAWN_TOGGLES")));
    }
}

}  // namespace

// Takes adapter ContextOptions::adapterIndex of a new instance and requests a device on it.
// Used at creation and again after a device loss (a WebGPU adapter hands out one device, so
// recovery asks for a new adapter too).
Result<void> Context::acquireDevice() {
    const ContextOptions& options = mOptions;
    mAdapter = nullptr;
    mDevice = nullptr;
    mQueue = nullptr;
    ENCORE_TRY_ASSIGN(auto enumerated,
                      enumerateAdapters(options.allowNullBackend, options.allowUnsafeApis));
    if (options.adapterIndex >= enumerated.adapters.size()) {
        return noSuchAdapter(options.adapterIndex, enumerated.descriptions);
    }
    mInstance = std::move(enumerated.instance);
    mAdapter = std::move(enumerated.adapters[options.adapterIndex]);
    mAdapterDescription = std::move(enumerated.descriptions[options.adapterIndex]);
    const AdapterDescription& description = mAdapterDescription;

    DeviceRequest request;
    fillDeviceRequest(request, options, mAdapter);
    wgpu::DawnTogglesDescriptor toggles;
    toggles.disabledToggleCount = request.disabledToggles.size();
    toggles.disabledToggles = request.disabledToggles.data();
    toggles.enabledToggleCount = request.enabledToggles.size();
    toggles.enabledToggles = request.enabledToggles.data();

    wgpu::DeviceDescriptor deviceDescriptor{};
    deviceDescriptor.nextInChain = &toggles;
    deviceDescriptor.label = "encore device";
    deviceDescriptor.requiredFeatureCount = request.features.size();
    deviceDescriptor.requiredFeatures = request.features.data();
    // Dawn raises requested limits below WebGPU's defaults to the defaults; mLimits applies them.
    wgpu::Limits adapterLimits{};
    if (mAdapter.GetLimits(&adapterLimits) != wgpu::Status::Success) {
        adapterLimits.maxSampledTexturesPerShaderStage =
            DeviceLimits{}.maxSampledTexturesPerShaderStage;
    }
    const wgpu::Limits required = requiredLimits(options.limitOverrides, adapterLimits);
    deviceDescriptor.requiredLimits = &required;
    ErrorLog* errorLog = mErrors.get();
    deviceDescriptor.SetUncapturedErrorCallback(
        [](const wgpu::Device&, wgpu::ErrorType type, wgpu::StringView message, ErrorLog* log) {
            if (type == wgpu::ErrorType::OutOfMemory) {
                std::lock_guard lock(log->mutex);
                log->outOfMemory = true;
            }
            log->record("WebGPU " + errorTypeName(type) + ": " + toString(message));
        },
        errorLog);
    deviceDescriptor.SetDeviceLostCallback(
        wgpu::CallbackMode::AllowSpontaneous,
        [](const wgpu::Device&, wgpu::DeviceLostReason reason, wgpu::StringView message,
           ErrorLog* log) {
            if (reason == wgpu::DeviceLostReason::Destroyed ||
                reason == wgpu::DeviceLostReason::CallbackCancelled) {
                return;  // Our own shutdown.
            }
            {
                std::lock_guard lock(log->mutex);
                log->lost = true;
            }
            log->record("WebGPU device lost: " + toString(message));
        },
        errorLog);

    std::string deviceMessage;
    mInstance.WaitAny(mAdapter.RequestDevice(&deviceDescriptor, wgpu::CallbackMode::WaitAnyOnly,
                                             [&](wgpu::RequestDeviceStatus status,
                                                 wgpu::Device device, wgpu::StringView message) {
                                                 if (status == wgpu::RequestDeviceStatus::Success) {
                                                     mDevice = std::move(device);
                                                 } else {
                                                     deviceMessage = toString(message);
                                                 }
                                             }),
                      UINT64_MAX);
    if (!mDevice) {
        return makeError(ErrorCode::DeviceError, "Creating a WebGPU device on '" +
                                                     description.name + "' failed (" +
                                                     deviceMessage + ").");
    }
    mQueue = mDevice.GetQueue();
    mLimits = DeviceLimits::of(mDevice, options.limitOverrides);
    return {};
}

std::optional<std::uint64_t> Context::mappingBudget() const {
    if (mAdapterDescription.adapterType != wgpu::AdapterType::CPU ||
        mAdapterDescription.backend != wgpu::BackendType::Vulkan) {
        return std::nullopt;
    }
    std::uint64_t maxMapCount = 65530;  // The kernel's default.
    if (std::FILE* file = std::fopen("/proc/sys/vm/max_map_count", "r")) {
        unsigned long long value = 0;
        if (std::fscanf(file, "%llu", &value) == 1) {
            maxMapCount = value;
        }
        std::fclose(file);
    }
    // Mappings already in use count against the limit (earlier scenes whose objects Dawn has
    // not released yet among them); leave room for the heap and Dawn's own allocations.
    std::uint64_t inUse = 0;
    if (std::FILE* maps = std::fopen("/proc/self/maps", "r")) {
        for (int c = std::fgetc(maps); c != EOF; c = std::fgetc(maps)) {
            inUse += c == '\n';
        }
        std::fclose(maps);
    }
    constexpr std::uint64_t kReserved = 8000;
    return maxMapCount > inUse + kReserved ? maxMapCount - inUse - kReserved : 0;
}

bool Context::hasFeature(wgpu::FeatureName feature) const {
    return mDevice.HasFeature(feature);
}

bool Context::wait(const wgpu::Future& future, std::uint64_t timeoutNs) const {
    if (mWaitMode == WaitMode::Spin && timeoutNs == UINT64_MAX) {
        wgpu::WaitStatus status;
        do {
            status = mInstance.WaitAny(future, 0);
        } while (status == wgpu::WaitStatus::TimedOut);
        return status == wgpu::WaitStatus::Success;
    }
    return mInstance.WaitAny(future, timeoutNs) == wgpu::WaitStatus::Success;
}

void Context::waitForIdle() const {
    wait(mQueue.OnSubmittedWorkDone(wgpu::CallbackMode::WaitAnyOnly,
                                    [](wgpu::QueueWorkDoneStatus, wgpu::StringView) {}));
}

std::size_t Context::errorCount() const {
    std::lock_guard lock(mErrors->mutex);
    return mErrors->errors.size();
}

std::vector<std::string> Context::takeErrors() {
    std::lock_guard lock(mErrors->mutex);
    mErrors->outOfMemory = false;
    return std::exchange(mErrors->errors, {});
}

Result<void> Context::recreateDevice() {
    if (mDevice) {
        mDevice.Destroy();  // Resolves the old device's callbacks (as Destroyed) before reuse.
    }
    {
        std::lock_guard lock(mErrors->mutex);
        mErrors->lost = false;
        mErrors->outOfMemory = false;
        mErrors->errors.clear();
    }
    return acquireDevice();
}

bool Context::deviceLost() const {
    std::lock_guard lock(mErrors->mutex);
    return mErrors->lost;
}

Result<void> Context::checkNoErrors(const std::string& what) {
    // Errors may be delivered from Dawn's event processing; let pending ones arrive first.
    mInstance.ProcessEvents();
    bool outOfMemory = false;
    {
        std::lock_guard lock(mErrors->mutex);
        outOfMemory = mErrors->outOfMemory;
    }
    auto errors = takeErrors();
    if (deviceLost()) {
        // The loss explains every later error; name it alone, with its own exit code.
        std::string reason = "no reason given";
        for (const std::string& error : errors) {
            if (error.starts_with("WebGPU device lost: ")) {
                reason = error.substr(20);
            }
        }
        return makeError(ErrorCode::DeviceError,
                         what + ": the GPU device was lost (" + reason + ").");
    }
    if (errors.empty()) {
        return {};
    }
    std::string message = what + " raised " + std::to_string(errors.size()) + " WebGPU error" +
                          (errors.size() == 1 ? "" : "s") + "; the first: " + errors.front();
    if (outOfMemory) {
        // Not the input's fault nor Encore's: a smaller scene or target may fit.
        const std::string prefix = "WebGPU " + errorTypeName(wgpu::ErrorType::OutOfMemory) + ": ";
        std::string_view reason = errors.front();
        for (const std::string& error : errors) {
            if (error.starts_with(prefix)) {
                reason = std::string_view(error).substr(prefix.size());
                break;
            }
        }
        return outOfMemoryError(what, reason);
    }
    return makeError(ErrorCode::ValidationError, std::move(message));
}

}  // namespace encore::gpu
