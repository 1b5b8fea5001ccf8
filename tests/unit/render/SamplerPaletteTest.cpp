#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <vector>

#include "render/SamplerPalette.h"

// A material's sampler palette on the CPU: which samplers it binds and which entry each texture
// slot samples with, exact while the palette has room and the nearest state past it.

namespace encore::render {
namespace {

using SlotSamplers = std::array<std::optional<std::size_t>, kMaterialTextureSlotCount>;

scene::Sampler sampler(scene::Wrap wrapS, scene::Wrap wrapT, scene::Filter mag) {
    scene::Sampler state;
    state.wrapS = wrapS;
    state.wrapT = wrapT;
    state.magFilter = mag;
    return state;
}

constexpr auto kRepeat = scene::Wrap::Repeat;
constexpr auto kClamp = scene::Wrap::ClampToEdge;
constexpr auto kMirror = scene::Wrap::MirroredRepeat;
constexpr auto kLinear = scene::Filter::Linear;
constexpr auto kNearest = scene::Filter::Nearest;

TEST(SamplerPaletteTest, SlotsSharingASamplerShareAnEntry) {
    const std::vector<scene::Sampler> states = {scene::Sampler{}, sampler(kClamp, kClamp, kLinear)};
    SlotSamplers slots;
    slots[std::size_t(TextureSlot::BaseColor)] = 1;
    slots[std::size_t(TextureSlot::Normal)] = 0;
    slots[std::size_t(TextureSlot::Emissive)] = 1;
    const SamplerPalette palette = makeSamplerPalette(slots, states, 0);
    EXPECT_EQ(palette.samplers, (std::vector<std::size_t>{1, 0}));
    EXPECT_EQ(palette.slotEntries[std::size_t(TextureSlot::BaseColor)], 0u);
    EXPECT_EQ(palette.slotEntries[std::size_t(TextureSlot::Normal)], 1u);
    EXPECT_EQ(palette.slotEntries[std::size_t(TextureSlot::Emissive)], 0u);
    EXPECT_EQ(palette.slotEntries[std::size_t(TextureSlot::Occlusion)], 0u);  // No texture.
    EXPECT_TRUE(palette.approximated.empty());
}

TEST(SamplerPaletteTest, AMaterialWithoutTexturesBindsTheFallback) {
    const std::vector<scene::Sampler> states = {scene::Sampler{}, scene::Sampler{}};
    const SamplerPalette palette = makeSamplerPalette(SlotSamplers{}, states, 1);
    EXPECT_EQ(palette.samplers, (std::vector<std::size_t>{1}));
    EXPECT_TRUE(palette.approximated.empty());
}

// Six distinct states in six slots: the first four (in slot order) are bound exactly, the last
// two sample with the nearest of them, and are named.
TEST(SamplerPaletteTest, SamplersPastThePaletteTakeTheNearestEntry) {
    static_assert(kMaterialSamplerCount == 4, "The test fills the palette with four states.");
    const std::vector<scene::Sampler> states = {
        sampler(kRepeat, kRepeat, kLinear),   // 0
        sampler(kClamp, kClamp, kLinear),     // 1
        sampler(kMirror, kMirror, kLinear),   // 2
        sampler(kRepeat, kClamp, kLinear),    // 3
        sampler(kClamp, kClamp, kNearest),    // 4: nearest is 1 (filter differs).
        sampler(kMirror, kMirror, kNearest),  // 5: nearest is 2.
    };
    SlotSamplers slots;
    for (std::size_t i = 0; i < states.size(); ++i) {
        slots[i] = i;
    }
    const SamplerPalette palette = makeSamplerPalette(slots, states, 0);
    EXPECT_EQ(palette.samplers, (std::vector<std::size_t>{0, 1, 2, 3}));
    for (std::uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(palette.slotEntries[i], i);
    }
    EXPECT_EQ(palette.slotEntries[4], 1u);
    EXPECT_EQ(palette.slotEntries[5], 2u);
    EXPECT_EQ(palette.approximated, (std::vector<TextureSlot>{TextureSlot(4), TextureSlot(5)}));
}

TEST(SamplerPaletteTest, WrapModesWeighMoreThanFilters) {
    const scene::Sampler base = sampler(kRepeat, kRepeat, kLinear);
    EXPECT_EQ(samplerDistance(base, base), 0u);
    scene::Sampler noMips = base;
    noMips.useMipmaps = false;
    noMips.mipmapFilter = scene::Filter::Nearest;  // Ignored without mipmaps.
    EXPECT_GT(samplerDistance(base, sampler(kClamp, kRepeat, kLinear)),
              samplerDistance(base, sampler(kRepeat, kRepeat, kNearest)));
    EXPECT_GT(samplerDistance(base, sampler(kClamp, kRepeat, kLinear)),
              samplerDistance(base, noMips));
    EXPECT_EQ(samplerDistance(base, noMips), samplerDistance(noMips, base));
}

}  // namespace
}  // namespace encore::render
