#pragma once

// A material's sampler palette: the few samplers its bind group holds (kMaterialSamplerCount),
// shared by its texture slots. Each slot's uniform names its palette entry and material.wgsl
// samples through that entry, so the slot count is not bound by the 16 samplers a shader stage
// may bind. A material whose textures use more distinct sampler states than the palette holds
// (rare: glTF files mostly use one or two) keeps the first ones in slot order, base colour
// first, exactly; each later slot samples with the entry nearest its own state
// (samplerDistance), and the caller warns.
//
// CPU-only: MaterialResources builds one per material; unit tests call it without a device.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "encore/scene/SceneData.h"
#include "render/MaterialSlots.h"

namespace encore::render {

struct SamplerPalette {
    // The palette's samplers, as indices into the caller's sampler states, in binding order
    // (materialSampler0, 1, ...); at most kMaterialSamplerCount, at least one.
    std::vector<std::size_t> samplers;
    // Each slot's entry in `samplers` (0 for a slot without a texture: any sampler reads the
    // 1-pixel default alike).
    std::array<std::uint32_t, kMaterialTextureSlotCount> slotEntries{};
    // Slots whose own sampler did not fit; they sample with the nearest entry instead.
    std::vector<TextureSlot> approximated;
};

// How unlike two sampler states sample: 0 when alike; a different wrap mode (which changes
// what a whole tiled texture shows) counts more than a different filter.
std::uint32_t samplerDistance(const scene::Sampler& a, const scene::Sampler& b);

// The palette of a material whose slot i samples with states[*slotSamplers[i]] (nullopt: the
// slot has no texture). `fallback` is the palette's only entry when no slot has a texture.
SamplerPalette makeSamplerPalette(
    std::span<const std::optional<std::size_t>, kMaterialTextureSlotCount> slotSamplers,
    std::span<const scene::Sampler> states,
    std::size_t fallback);

}  // namespace encore::render
