#pragma once

// PNGs of float RGBA images whose values lie in [0, 1] (normals mapped n * 0.5 + 0.5, object
// coordinates), in 8 or 16 bits per channel: what the float passes store when asked for PNG.

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"

namespace encore::batch {

// `value` clamped to [0, 1] and rounded to the nearest of 2^bitDepth - 1 steps: the sample
// encodeRgbaPng stores (and render_views returns as an integer array).
std::uint32_t pngSample(float value, std::uint8_t bitDepth);

// `rgba` holds width x height x 4 floats, row after row; each is clamped to [0, 1] and rounded
// to the nearest of 2^bitDepth - 1 steps. `bitDepth` is 8 or 16.
Result<std::vector<std::uint8_t>> encodeRgbaPng(std::span<const float> rgba,
                                                std::uint32_t width,
                                                std::uint32_t height,
                                                std::uint8_t bitDepth,
                                                image::PngCompression compression);

}  // namespace encore::batch
