#include "render/SamplerPalette.h"

#include <algorithm>
#include <cassert>

namespace encore::render {

std::uint32_t samplerDistance(const scene::Sampler& a, const scene::Sampler& b) {
    // Wrap modes decide which texels a coordinate reads; filters only how they blend.
    std::uint32_t distance = 0;
    distance += a.wrapS != b.wrapS ? 8 : 0;
    distance += a.wrapT != b.wrapT ? 8 : 0;
    distance += a.useMipmaps != b.useMipmaps ? 4 : 0;
    distance += a.magFilter != b.magFilter ? 2 : 0;
    distance += a.minFilter != b.minFilter ? 2 : 0;
    distance += a.useMipmaps && b.useMipmaps && a.mipmapFilter != b.mipmapFilter ? 1 : 0;
    return distance;
}

SamplerPalette makeSamplerPalette(
    std::span<const std::optional<std::size_t>, kMaterialTextureSlotCount> slotSamplers,
    std::span<const scene::Sampler> states,
    std::size_t fallback) {
    SamplerPalette palette;
    // Exact entries first, in slot order, while there is room.
    std::vector<std::uint32_t> overflow;
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        if (!slotSamplers[slot]) {
            continue;
        }
        const std::size_t sampler = *slotSamplers[slot];
        assert(sampler < states.size());
        const auto found = std::find(palette.samplers.begin(), palette.samplers.end(), sampler);
        if (found != palette.samplers.end()) {
            palette.slotEntries[slot] = std::uint32_t(found - palette.samplers.begin());
        } else if (palette.samplers.size() < kMaterialSamplerCount) {
            palette.slotEntries[slot] = std::uint32_t(palette.samplers.size());
            palette.samplers.push_back(sampler);
        } else {
            overflow.push_back(slot);
        }
    }
    // Then the slots left over, each to the nearest entry (the first of equals).
    for (const std::uint32_t slot : overflow) {
        const scene::Sampler& wanted = states[*slotSamplers[slot]];
        std::uint32_t best = 0;
        std::uint32_t bestDistance = UINT32_MAX;
        for (std::uint32_t entry = 0; entry < palette.samplers.size(); ++entry) {
            const std::uint32_t distance = samplerDistance(wanted, states[palette.samplers[entry]]);
            if (distance < bestDistance) {
                best = entry;
                bestDistance = distance;
            }
        }
        palette.slotEntries[slot] = best;
        palette.approximated.push_back(TextureSlot(slot));
    }
    if (palette.samplers.empty()) {
        palette.samplers.push_back(fallback);
    }
    return palette;
}

}  // namespace encore::render
