#pragma once

// How many colour targets a scene pass has: the scene colour, and with pass targets
// (RendererOptions::passTargets, render/PassTargets.h) four more of the same format.

#include <cstdint>

namespace encore::render {

inline constexpr std::uint32_t kPassTargetCount = 4;  // Normal, albedo, material, depth + id.
inline constexpr std::uint32_t kMaxSceneColorTargets = 1 + kPassTargetCount;
// The bytes per sample the five rgba16float targets need (maxColorAttachmentBytesPerSample;
// WebGPU's default is 32).
inline constexpr std::uint32_t kPassTargetBytesPerSample = kMaxSceneColorTargets * 8;

}  // namespace encore::render
