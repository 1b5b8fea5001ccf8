#pragma once

// Decoding an image to fit within a size (scene::LoadOptions::maxImageDimension): a JPEG decodes
// at a fraction of its size where libjpeg can (ImageDecoders.h), then every format is
// box-filtered (ImageResize.h) down to the largest size with its aspect ratio whose sides are at
// most the limit, so that one huge texture costs neither the memory nor the upload of its size.

#include <cstdint>
#include <span>

#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"
#include "image/ImageResize.h"

namespace encore::image {

struct FittedDecode {
    ImageRgba8 image;
    ImageSize source;  // The size the file declares (that of `image` unless it was downscaled).
};

// decodeImage, then downscaled to fit within `maxDimension` (0: kept as decoded). `encoding`
// says how the colour channels are averaged.
Result<FittedDecode> decodeImageWithin(std::span<const std::uint8_t> encoded,
                                       std::uint32_t maxDimension,
                                       PixelEncoding encoding);

// A PNG larger than checkDecodable allows, decoded row by row and box-filtered to fit within
// `maxDimension` as the rows come (PngRowDownscale.cpp): its memory is the result's. Interlaced
// ones are refused (LimitExceeded).
Result<FittedDecode> decodeLargePngWithin(std::span<const std::uint8_t> encoded,
                                          std::uint32_t maxDimension,
                                          PixelEncoding encoding);

}  // namespace encore::image
