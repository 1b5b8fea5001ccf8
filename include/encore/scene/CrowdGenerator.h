#pragma once

// Generates an animated crowd for benchmarks of animation at scale: `characters` copies of one
// skinned character (a four-segment column skinned to a chain of four joints, each vertex
// weighing its two nearest joints) on a square grid in the XZ plane, all drawing one mesh. One
// animation ("sway", 1 second) turns every joint back and forth; character k plays it with
// its own time offset, baked into its samplers' key times (k × 0.37 s, modulo 1 s), so
// neighbours never move in step. All characters share the key values and the inverse bind
// matrices (the skeleton's bind pose is at the origin; each character's root node places it).
// The output is a self-contained .glb.

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"

namespace encore::scene {

struct CrowdOptions {
    std::uint32_t characters = 1000;
};

inline constexpr std::uint32_t kMaxCrowdCharacters = 200'000;
inline constexpr std::uint32_t kCrowdJointsPerCharacter = 4;
inline constexpr std::uint32_t kCrowdNodesPerCharacter = 2 + kCrowdJointsPerCharacter;

// The crowd as .glb bytes; an error for 0 or more than kMaxCrowdCharacters characters.
Result<std::vector<std::uint8_t>> generateCrowdGlb(const CrowdOptions& options);

}  // namespace encore::scene
