#pragma once

// The stages whose GPU time a renderer reports through gpu::StageTimestamps
// (Renderer::setStageTimestamps), named for reports. ReadbackCopy is timed by the caller that
// copies the target out (gpu::TextureReadbackRing::enqueue).

#include <array>
#include <cstdint>
#include <string_view>

namespace encore::render {

enum class GpuStage : std::uint32_t {
    Mipmaps,       // Filling the mip chains of a scene's textures (MipmapGenerator).
    Scene,         // The scene passes: one per view, with their multisample resolve.
    ToneMapping,   // The HDR scene colour into the 8-bit output (ToneMapper).
    ReadbackCopy,  // The output into a read-back buffer.
    // What a strategy records before the scene passes (Strategy::beforePass): GPU culling, and
    // the visibility strategy's cull, compute raster, bins and shading.
    BeforePasses,
};

inline constexpr std::uint32_t kGpuStageCount = 5;

inline constexpr std::array<std::string_view, kGpuStageCount> kGpuStageNames = {
    "mipmaps", "scene passes", "tone mapping", "read-back copy", "before the scene passes"};

constexpr std::uint32_t gpuStageIndex(GpuStage stage) {
    return static_cast<std::uint32_t>(stage);
}

}  // namespace encore::render
