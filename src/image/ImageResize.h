#pragma once

// Downscaling RGBA8 images on the CPU, for images larger than a device can hold as a texture
// (maxTextureDimension2D). The filter is an area-weighted box: every destination pixel is the
// average of the source area it covers, fractional pixels weighted by their coverage, so any
// ratio (not only powers of two) keeps the image's mean. Colour channels of sRGB-encoded images
// are averaged in linear light (averaging encoded values darkens edges); alpha is always linear.

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/ReusedBlocks.h"

namespace encore::image {

struct ImageSize {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    bool operator==(const ImageSize&) const = default;
};

// The largest size with the aspect ratio of width x height (rounded to whole pixels, at least
// 1x1) whose sides are at most maxDimension. An image that already fits keeps its size.
ImageSize fitWithin(ImageSize size, std::uint32_t maxDimension);

enum class PixelEncoding : std::uint8_t {
    Srgb,    // Colour channels carry the sRGB transfer function.
    Linear,  // Non-colour data (normals, roughness) or linear colour.
};

// Box-filters `pixels` (source.width * source.height * 4 bytes, rows top to bottom) down to
// `target`, whose sides must be no larger than the source's and at least 1. Memory beyond the
// result is one row of the target.
ReusedBytes downscaleRgba8(std::span<const std::uint8_t> pixels,
                           ImageSize source,
                           ImageSize target,
                           PixelEncoding encoding);

// The same filter for linear RGB floats (HDR panoramas): width * height * 3 floats.
std::vector<float> downscaleRgbFloat(std::span<const float> pixels,
                                     ImageSize source,
                                     ImageSize target);

}  // namespace encore::image
