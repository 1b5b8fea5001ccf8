#pragma once

// The device limits Encore checks its own allocations against, so that a scene beyond them
// fails with an error naming the limit and the numbers instead of a WebGPU validation error.
//
// They are the device's limits, tightened by ContextOptions::limitOverrides. The overrides exist
// because Dawn raises any requested limit that is worse than WebGPU's default to that default
// (requesting maxTextureDimension2D = 256 yields 8192): a device with small limits cannot be
// had, yet tests must show what happens beyond them without gigabyte-sized scenes. The context
// still requests the overrides from Dawn, so an implementation that grants smaller limits
// enforces them too.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>
#include <string_view>

#include "encore/core/Result.h"

namespace encore::gpu {

// Limits to apply below the device's own; absent ones leave the device's value.
struct LimitOverrides {
    std::optional<std::uint32_t> maxTextureDimension2D;
    std::optional<std::uint64_t> maxBufferSize;
    std::optional<std::uint64_t> maxStorageBufferBindingSize;
    std::optional<std::uint32_t> maxSampledTexturesPerShaderStage;
};

// The most sampled textures per shader stage the context asks for (or the adapter's limit, when
// lower): room for material texture slots beyond WebGPU's default of 16. Renderer::create
// checks that the device offers as many as its pipelines bind (render/BindingLimits.h).
inline constexpr std::uint32_t kRequestedSampledTexturesPerShaderStage = 48;
// Colour attachment bytes per sample that devices ask for (where the adapter has them): a scene
// pass with pass targets (RendererOptions::passTargets) writes five rgba16float targets, 40.
inline constexpr std::uint32_t kRequestedColorAttachmentBytesPerSample = 64;

struct DeviceLimits {
    // WebGPU's defaults, which every device offers at least.
    std::uint32_t maxTextureDimension2D = 8192;
    std::uint64_t maxBufferSize = 268435456;
    std::uint64_t maxStorageBufferBindingSize = 134217728;
    std::uint32_t minUniformBufferOffsetAlignment = 256;
    std::uint32_t maxSampledTexturesPerShaderStage = 16;
    std::uint32_t maxColorAttachmentBytesPerSample = 32;

    // The limits `device` reports, tightened by `overrides`.
    static DeviceLimits of(const wgpu::Device& device, const LimitOverrides& overrides = {});
};

// wgpu::Limits for DeviceDescriptor: `overrides`, and maxSampledTexturesPerShaderStage raised
// to kRequestedSampledTexturesPerShaderStage or `adapter`'s limit, whichever is lower (an
// override wins), maxColorAttachmentBytesPerSample likewise to
// kRequestedColorAttachmentBytesPerSample; everything else undefined.
wgpu::Limits requiredLimits(const LimitOverrides& overrides, const wgpu::Limits& adapter);

// LimitExceeded when a buffer of `bytes` exceeds maxBufferSize, reading "<what>: a buffer of
// <bytes> bytes, larger than the device's maxBufferSize (<limit> bytes)."; `what` names what
// needs the buffer, e.g. "The instance transforms of 2000000 instances".
Result<void> checkBufferSize(const DeviceLimits& limits,
                             std::uint64_t bytes,
                             std::string_view what);
// As checkBufferSize, and also against maxStorageBufferBindingSize, for a buffer bound whole as
// a storage binding.
Result<void> checkStorageBinding(const DeviceLimits& limits,
                                 std::uint64_t bytes,
                                 std::string_view what);

}  // namespace encore::gpu
