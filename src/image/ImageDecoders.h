#pragma once

// The decoders behind decodeImage, one per library: PNG with libspng (its common case with
// libdeflate's inflate), JPEG with libjpeg-turbo
// (both faster than stb_image on the large textures that dominate loading), WebP with libwebp
// (EXT_texture_webp), and stb_image for what those do not take (CMYK JPEGs, the other formats
// stb reads). Each reads the header,
// has checkDecodable approve the size, and only then allocates and decodes.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

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
bool isWebp(std::span<const std::uint8_t> encoded);

// A PNG's unsigned 32-bit numbers (chunk lengths, IHDR's sizes) are big-endian.
inline std::uint32_t pngUint32(const std::uint8_t* bytes) {
    return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 |
           std::uint32_t(bytes[2]) << 8 | std::uint32_t(bytes[3]);
}

// One chunk of a PNG: its four-letter type, its data, and where it starts in the file.
struct PngChunk {
    std::string_view type;
    std::span<const std::uint8_t> data;
    std::size_t offset = 0;
};

// Hands the chunks after the signature to `visit` in order, up to and including IEND or until
// fewer bytes than a chunk's 12 remain; `visit` returns false to stop early. Fails, naming the
// chunk's offset and both sizes, on a chunk that declares more bytes than follow, before `visit`
// sees it: a corrupt length must not make a decoder size a buffer from it (a fuzzer finding
// against stb_image: an IDAT declaring 1.4 GB in a 42 kB file asked for 2 GiB).
Result<void> forEachPngChunk(std::span<const std::uint8_t> encoded,
                             const std::function<bool(const PngChunk&)>& visit);

Result<ImageRgba8> decodePng(std::span<const std::uint8_t> encoded);
// The common case of decodePng, faster (PngLibdeflateDecoder.cpp): 8-bit, not interlaced, and
// nothing wrong with it (every chunk fits, forEachPngChunk). Empty for everything else, which
// decodePng leaves to libspng.
std::optional<ImageRgba8> decodePngWithLibdeflate(std::span<const std::uint8_t> encoded);
// Four-channel (CMYK, YCCK) JPEGs, which libjpeg-turbo cannot convert to RGBA, go to stb_image.
// With `maxDimension`, a baseline JPEG larger than it decodes at the smallest of 1/2, 1/4 and
// 1/8 of its size that stays at least that large (libjpeg's DCT scaling), and the size limits
// apply to what is decoded: a 16k texture then costs what a 4k one does.
Result<ImageRgba8> decodeJpeg(std::span<const std::uint8_t> encoded,
                              std::uint32_t maxDimension = 0);
// Still WebP images, lossy or lossless (WebpDecoder.cpp); animated ones are refused.
Result<ImageRgba8> decodeWebp(std::span<const std::uint8_t> encoded);
Result<ImageRgba8> decodeWithStb(std::span<const std::uint8_t> encoded);

}  // namespace encore::image
