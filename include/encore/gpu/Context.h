#pragma once

// gpu::Context owns the WebGPU instance, adapter, device and queue of a headless Dawn setup.
//
// Creation refuses Dawn's Null backend (which Dawn falls back to, silently, when no usable Vulkan
// driver exists, and which renders nothing) unless ContextOptions::allowNullBackend asks for a
// validation-only run. Every uncaptured WebGPU error (validation, out-of-memory, internal) is
// reported through encore::log and recorded, so tests and tools can fail on any of them.

#include <webgpu/webgpu_cpp.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"

namespace encore::gpu {

struct ContextOptions {
    // Which adapter of listAdapters() to use: 0, the first, is the one Dawn would offer by
    // itself (the highest-performance Vulkan adapter).
    std::size_t adapterIndex = 0;
    bool allowNullBackend = false;
    // Requests TimestampQuery when the adapter has it and disables Dawn's timestamp
    // quantization (~65 us granularity otherwise), for benchmarks.
    bool timestamps = false;
    // Features requested only when the adapter supports them (e.g. IndirectFirstInstance).
    std::vector<wgpu::FeatureName> optionalFeatures;
    // Turns on Dawn's allow_unsafe_apis toggle for the adapter request and the device: Dawn
    // offers some features only with it (AtomicVec2uMinMax, which the visibility strategy's
    // 64-bit atomics need; render::requestVisibilityFeatures asks for both). Off by default.
    bool allowUnsafeApis = false;
    // Limits below the device's, for tests of what lies beyond them (see DeviceLimits.h).
    LimitOverrides limitOverrides;
};

struct AdapterDescription {
    std::size_t index = 0;  // In listAdapters()' order: what ContextOptions::adapterIndex names.
    std::string name;       // e.g. "llvmpipe (LLVM 19.1.7, 256 bits)"
    std::string vendor;
    std::string architecture;
    std::string driver;  // The driver description Dawn reports.
    wgpu::BackendType backend = wgpu::BackendType::Undefined;
    wgpu::AdapterType adapterType = wgpu::AdapterType::Unknown;

    // "llvmpipe (LLVM 19.1.7, 256 bits), Vulkan, CPU, driver Mesa 25.0.7"
    std::string summary() const;
};

std::string backendName(wgpu::BackendType backend);
std::string adapterTypeName(wgpu::AdapterType type);  // "discrete GPU", "CPU", ...

// Every adapter a Context may be created on, the one Dawn prefers first (discrete GPUs before
// integrated ones before CPU renderers such as lavapipe): the Vulkan adapters, or with
// `allowNullBackend` Dawn's Null adapter when there is no Vulkan one. Fails with NoAdapter when
// the list would be empty.
Result<std::vector<AdapterDescription>> listAdapters(bool allowNullBackend = false);

// The indices of the adapters that `--devices all` uses: every adapter of the same type as the
// first (all the GPUs of a GPU machine, without a CPU renderer it may also have).
std::vector<std::size_t> adaptersLike(std::span<const AdapterDescription> adapters,
                                      std::size_t first = 0);

// How the CPU waits for the GPU (waitForIdle, timestamp and buffer read-backs). Spin polls
// instead of sleeping in the driver: the core stays awake, so CPU work that follows a wait is
// not slowed by waking it from a deep idle state. Benchmarks spin; everything else blocks.
enum class WaitMode { Block, Spin };

class Context {
  public:
    static Result<Context> create(const ContextOptions& options = {});

    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;
    ~Context();

    const wgpu::Instance& instance() const { return mInstance; }
    const wgpu::Adapter& adapter() const { return mAdapter; }
    const wgpu::Device& device() const { return mDevice; }
    const wgpu::Queue& queue() const { return mQueue; }
    const AdapterDescription& adapterDescription() const { return mAdapterDescription; }
    bool hasFeature(wgpu::FeatureName feature) const;
    // The limits Encore sizes its allocations by: the device's, tightened by the overrides.
    const DeviceLimits& limits() const { return mLimits; }

    // How many more memory mappings the driver may create, when it maps memory per object and
    // crashes once the kernel refuses: Mesa's lavapipe maps each buffer and descriptor set
    // allocation, and segfaults when the process reaches vm.max_map_count (65,530 by default;
    // raise it with `sysctl -w vm.max_map_count=262144`). The budget is the limit minus the
    // mappings the process holds now. Code that would create more objects than this returns an
    // error instead. nullopt: no such driver.
    std::optional<std::uint64_t> mappingBudget() const;

    // Waits until the future completes, as setWaitMode says. Returns false on timeout.
    bool wait(const wgpu::Future& future, std::uint64_t timeoutNs = UINT64_MAX) const;
    // Waits until all submitted work has completed on the GPU.
    void waitForIdle() const;
    void setWaitMode(WaitMode mode) { mWaitMode = mode; }
    WaitMode waitMode() const { return mWaitMode; }

    // Errors reported by the device since creation (or since the last takeErrors()).
    std::size_t errorCount() const;
    std::vector<std::string> takeErrors();
    bool deviceLost() const;
    // After a loss: requests a new adapter and device (same options) and forgets the recorded
    // errors. Every object of the old device is useless; owners rebuild theirs (see
    // render::Renderer::recoverFromDeviceLoss).
    Result<void> recreateDevice();

    // Returns a ValidationError naming the first recorded error, an OutOfMemory error when one
    // of them was an out-of-memory error, a DeviceError when the device was lost, or success
    // when none occurred.
    Result<void> checkNoErrors(const std::string& what);

  private:
    struct ErrorLog;
    Context() = default;
    Result<void> acquireDevice();

    wgpu::Instance mInstance;
    wgpu::Adapter mAdapter;
    wgpu::Device mDevice;
    wgpu::Queue mQueue;
    WaitMode mWaitMode = WaitMode::Block;
    AdapterDescription mAdapterDescription;
    DeviceLimits mLimits;
    ContextOptions mOptions;
    std::shared_ptr<ErrorLog> mErrors;
};

}  // namespace encore::gpu
