#pragma once

// PNG decoding (libspng), JPEG decoding (libjpeg-turbo; stb_image for CMYK JPEGs and the other
// formats stb reads) and PNG encoding (libdeflate). This is the only place an image library
// appears.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/core/ReusedBlocks.h"

namespace encore::image {

// Images larger than this on either side are refused before decoding (WebGPU's default
// maxTextureDimension2D is 8192; this guards against absurd headers).
inline constexpr std::uint32_t kMaxImageDimension = 16384;
// And larger than this in area: decoding needs about twice width x height x 4 bytes at once
// (the fuzzer found a 16384 x 16384 header asking for 2 GiB), and no GPU texture Encore creates
// is larger than 8192 x 8192.
inline constexpr std::uint64_t kMaxImagePixels = 8192ull * 8192ull;
// And by the bytes of the decoded samples (width x height x channels x bytes per channel, as
// stored in the file): a 16-bit RGBA image of 8192 x 8192 needs 512 MiB raw plus its 16-bit
// RGBA copy before conversion to 8 bits (in stb_image), and stb's inflate doubles its buffer
// past that (the fuzzer found one asking for 2 GiB). 256 MiB admits every 8-bit image of
// kMaxImagePixels.
inline constexpr std::uint64_t kMaxDecodedImageBytes = 256ull << 20;

struct ImageRgba8 {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    // width * height * 4 bytes, rows top to bottom; decoders write them into reused blocks.
    ReusedBytes pixels;

    std::uint8_t* pixel(std::uint32_t x, std::uint32_t y) { return &pixels[(y * width + x) * 4]; }
    const std::uint8_t* pixel(std::uint32_t x, std::uint32_t y) const {
        return &pixels[(y * width + x) * 4];
    }
};

// Decodes PNG, JPEG or (still) WebP bytes into RGBA8: grey, grey-alpha, palette and RGB images
// get their colours expanded and alpha 255 (tRNS applied), 16-bit samples keep their high byte.
Result<ImageRgba8> decodeImage(std::span<const std::uint8_t> encoded);

// How PNG encoding trades size for time (ImageCodec.cpp says how; on rendered 512x512 views,
// docs/benchmarks/2026-11-26-png-paeth-runs.md).
enum class PngCompression : std::uint8_t {
    // 8-bit: the Paeth filter and runs of a repeated byte (RunLengthDeflate.h), as small as
    // libdeflate's level 2 after Up; 16-bit: Up and libdeflate at level 2.
    Small,
    // The Up filter and runs, for bulk rendering where encoding limits the throughput: about
    // 30% less time than Small for 8-bit views 15-30% larger; 16-bit ids or depth half the
    // time of Small (ids as small, depth nearly three times larger).
    Fast,
};

// "small" or "fast", as `encore batch --png-compression` and Python's png_compression take it.
std::optional<PngCompression> pngCompressionFromName(std::string_view name);

Result<std::vector<std::uint8_t>> encodePng(const ImageRgba8& image,
                                            PngCompression compression = PngCompression::Small);

// A 16-bit greyscale image (depth maps), rows top to bottom.
struct ImageGray16 {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint16_t> pixels;  // width * height values.
};

// Encodes a 16-bit greyscale PNG.
Result<std::vector<std::uint8_t>> encodePng16(const ImageGray16& image,
                                              PngCompression compression = PngCompression::Small);
Result<void> writePng(const std::filesystem::path& path, const ImageRgba8& image);
Result<ImageRgba8> readImage(const std::filesystem::path& path);

}  // namespace encore::image
