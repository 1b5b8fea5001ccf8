#pragma once

// OpenEXR files in memory, written through the OpenEXR library (the batch writes them under
// partial names like its PNGs): the depth pass as one 32-bit float channel `Z`, the HDR pass as
// half-float `R`, `G`, `B`, `A` (premultiplied, as EXR defines its colour). Rows run top to
// bottom, as in the PNGs.

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"

namespace encore::batch {

// `depth` holds width x height floats (row after row); infinity stays infinity.
Result<std::vector<std::uint8_t>> encodeExrDepth(std::span<const float> depth,
                                                 std::uint32_t width,
                                                 std::uint32_t height);

// `rgba` holds width x height x 4 floats, stored as half floats.
Result<std::vector<std::uint8_t>> encodeExrRgbaHalf(std::span<const float> rgba,
                                                    std::uint32_t width,
                                                    std::uint32_t height);

}  // namespace encore::batch
