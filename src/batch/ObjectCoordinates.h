#pragma once

// The object-coordinates pass (--coordinates, NOCS-style; docs/batch.md#conventions): each
// pixel's surface position in the model's normalised box (ViewRig.h's normalization: the unit
// box centred at the origin) moved into [0, 1]^3, from a strip drawn through the position debug
// channel (world positions times coverage, the coverage in A) and read back as floats.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "batch/PassImages.h"
#include "encore/batch/ViewImages.h"
#include "encore/core/Result.h"

namespace encore::batch {

// RGBA floats, rows packed: normalization * position + 0.5 and the coverage; all 0 where nothing
// is drawn.
std::vector<float> objectCoordinates(const FloatStrip& strip, const glm::mat4& normalization);

// The encoded image: 16-bit RGBA PNG (each value clamped to [0, 1]) or half-float EXR.
Result<std::vector<std::uint8_t>> encodeCoordinates(const std::vector<float>& coordinates,
                                                    std::uint32_t width,
                                                    std::uint32_t height,
                                                    CoordinatesFormat format,
                                                    image::PngCompression compression);

}  // namespace encore::batch
