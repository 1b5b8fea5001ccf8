#pragma once

// How many sampled textures and samplers Encore's material pipelines bind in one shader stage
// (the fragment stage, and the compute stage of the visibility strategy's resolve), and the
// check that a device offers them. The count grows with the material texture slots
// (MaterialSlots.h); the samplers stay few, since the slots share a palette (SamplerPalette.h).

#include <cstdint>
#include <string_view>

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "render/MaterialSlots.h"

namespace encore::render {

// Group 0: the environment atlas and its sampler (scene_lighting.wgsl), and the transmission
// background read through that sampler (transmission.wgsl).
inline constexpr std::uint32_t kFrameSampledTextures = 2;
inline constexpr std::uint32_t kFrameSamplers = 1;

inline constexpr std::uint32_t kStageSampledTextures =
    kFrameSampledTextures + kMaterialTextureSlotCount;
inline constexpr std::uint32_t kStageSamplers = kFrameSamplers + kMaterialSamplerCount;
// WebGPU guarantees 16 samplers per stage, and Dawn offers no more.
static_assert(kStageSamplers <= 16, "The material sampler palette leaves no room for group 0's.");
static_assert(kStageSampledTextures <= gpu::kRequestedSampledTexturesPerShaderStage,
              "gpu::Context requests fewer sampled textures than the material pipelines bind.");

// LimitExceeded, naming `adapter` and both numbers, when the device's
// maxSampledTexturesPerShaderStage is below kStageSampledTextures.
Result<void> checkBindingLimits(const gpu::DeviceLimits& limits, std::string_view adapter);

}  // namespace encore::render
