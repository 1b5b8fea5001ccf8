#pragma once

// The decoders behind decodeImage, one per library: PNG with libspng (its common case with
// libdeflate's inflate), JPEG with libjpeg-turbo
// (both faster than stb_image on the large textures that dominate loading), and stb_image for
// what those two do not take (CMYK JPEGs, the other formats stb reads). Each reads the header,
// has checkDecodable approve the size, and only then allocates and decodes.

#include <cstdint>
#include <optional>
#include <span>

#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"

namespace encore::image {

// What a header says before any pixel is decoded.
struct ImageHeader {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t bitsPerChannel = 8;  // 16 for 16-bit PNGs.
};

// Refuses sizes beyond kMaxImageDimension, kMaxImagePixels and kMaxDecodedImageBytes, with the
// numbers in the message.
Result<void> checkDecodable(const ImageHeader& header);

bool isPng(std::span<const std::uint8_t> encoded);
bool isJpeg(std::span<const std::uint8_t> encoded);

Result<ImageRgba8> decodePng(std::span<const std::uint8_t> encoded);
// The common case of decodePng, faster (PngLibdeflateDecoder.cpp): 8-bit, not interlaced, and
// nothing wrong with it. Empty for everything else, which decodePng leaves to libspng; call it
// after checkPngChunks.
std::optional<ImageRgba8> decodePngWithLibdeflate(std::span<const std::uint8_t> encoded);
// Four-channel (CMYK, YCCK) JPEGs, which libjpeg-turbo cannot convert to RGBA, go to stb_image.
Result<ImageRgba8> decodeJpeg(std::span<const std::uint8_t> encoded);
Result<ImageRgba8> decodeWithStb(std::span<const std::uint8_t> encoded);

}  // namespace encore::image
