#include "encore/gpu/DeviceLimits.h"

#include <algorithm>
#include <string>

namespace encore::gpu {

namespace {

Result<void> checkLimit(std::uint64_t limit,
                        const char* limitName,
                        const char* needed,
                        std::uint64_t bytes,
                        std::string_view what) {
    if (bytes <= limit) {
        return {};
    }
    return makeError(ErrorCode::LimitExceeded, std::string(what) + ": " + needed + " of " +
                                                   std::to_string(bytes) +
                                                   " bytes, larger than the device's " + limitName +
                                                   " (" + std::to_string(limit) + " bytes).");
}

}  // namespace

DeviceLimits DeviceLimits::of(const wgpu::Device& device, const LimitOverrides& overrides) {
    wgpu::Limits reported{};
    DeviceLimits limits;
    if (device && device.GetLimits(&reported) == wgpu::Status::Success) {
        limits.maxTextureDimension2D = reported.maxTextureDimension2D;
        limits.maxBufferSize = reported.maxBufferSize;
        limits.maxStorageBufferBindingSize = reported.maxStorageBufferBindingSize;
        limits.minUniformBufferOffsetAlignment = reported.minUniformBufferOffsetAlignment;
        limits.maxSampledTexturesPerShaderStage = reported.maxSampledTexturesPerShaderStage;
        limits.maxColorAttachmentBytesPerSample = reported.maxColorAttachmentBytesPerSample;
    }
    if (overrides.maxTextureDimension2D) {
        limits.maxTextureDimension2D =
            std::min(limits.maxTextureDimension2D, *overrides.maxTextureDimension2D);
    }
    if (overrides.maxBufferSize) {
        limits.maxBufferSize = std::min(limits.maxBufferSize, *overrides.maxBufferSize);
    }
    if (overrides.maxStorageBufferBindingSize) {
        limits.maxStorageBufferBindingSize =
            std::min(limits.maxStorageBufferBindingSize, *overrides.maxStorageBufferBindingSize);
    }
    if (overrides.maxSampledTexturesPerShaderStage) {
        limits.maxSampledTexturesPerShaderStage = std::min(
            limits.maxSampledTexturesPerShaderStage, *overrides.maxSampledTexturesPerShaderStage);
    }
    // A binding never exceeds its buffer.
    limits.maxStorageBufferBindingSize =
        std::min(limits.maxStorageBufferBindingSize, limits.maxBufferSize);
    return limits;
}

wgpu::Limits requiredLimits(const LimitOverrides& overrides, const wgpu::Limits& adapter) {
    wgpu::Limits limits{};
    // Only as many as Encore may bind: a higher limit can cost binding memory on some backends.
    limits.maxSampledTexturesPerShaderStage =
        overrides.maxSampledTexturesPerShaderStage
            ? *overrides.maxSampledTexturesPerShaderStage
            : std::min(adapter.maxSampledTexturesPerShaderStage,
                       kRequestedSampledTexturesPerShaderStage);
    limits.maxColorAttachmentBytesPerSample =
        std::max(32u, std::min(adapter.maxColorAttachmentBytesPerSample,
                               kRequestedColorAttachmentBytesPerSample));
    if (overrides.maxTextureDimension2D) {
        limits.maxTextureDimension2D = *overrides.maxTextureDimension2D;
    }
    if (overrides.maxBufferSize) {
        limits.maxBufferSize = *overrides.maxBufferSize;
    }
    if (overrides.maxStorageBufferBindingSize) {
        limits.maxStorageBufferBindingSize = *overrides.maxStorageBufferBindingSize;
    }
    return limits;
}

Result<void> checkBufferSize(const DeviceLimits& limits,
                             std::uint64_t bytes,
                             std::string_view what) {
    return checkLimit(limits.maxBufferSize, "maxBufferSize", "a buffer", bytes, what);
}

Result<void> checkStorageBinding(const DeviceLimits& limits,
                                 std::uint64_t bytes,
                                 std::string_view what) {
    ENCORE_TRY(checkBufferSize(limits, bytes, what));
    return checkLimit(limits.maxStorageBufferBindingSize, "maxStorageBufferBindingSize",
                      "a storage binding", bytes, what);
}

}  // namespace encore::gpu
