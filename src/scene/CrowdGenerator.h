#pragma once

// Generates an animated crowd for benchmarks of animation at scale: `characters` copies of one
// skinned character (a four-segment column skinned to a chain of four joints, each vertex
// weighing its two nearest joints) on a square grid in the XZ plane, all drawing one mesh.
// Character k has its own animation ("sway k", 1 second) that turns its joints back and forth
// from the same key-time and key-value accessors as every other character's, played with its
// own time offset (extras.encoreTimeOffset = k × 0.37 s, modulo 1 s; see
// scene::Animation::timeOffset), so neighbours never move in step while the GPU stores one set
// of keyframes and one clock for the whole crowd. All characters share the inverse bind matrices
// too (the skeleton's bind pose is at the origin; each character's root node places it).
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
