#pragma once

// PNG writing in two steps that may run on different processors: the rows filtered for deflate
// (filterPngRows here, or a GPU pass that writes the same bytes: batch/PngRowsPass), then the
// filtered rows compressed into a file (pngOfFilteredRows). How each PngCompression filters and
// compresses: PngWriter.cpp.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"

namespace encore::image {

enum class PngColor : std::uint8_t { Gray = 0, Rgba = 6 };

// The PNG filters Encore writes: every row Up (the first None, as nothing is above it), or every
// row Paeth.
enum class PngRowFilter : std::uint8_t { Up, Paeth };

// The filter `compression` uses for samples of `bitDepth` bits (8 or 16).
PngRowFilter pngRowFilter(std::uint8_t bitDepth, PngCompression compression);

// Bytes per pixel, and the size of filtered rows: each row's bytes after its filter-type byte.
std::size_t pngBytesPerPixel(std::uint8_t bitDepth, PngColor color);
std::size_t filteredPngSize(std::uint32_t width,
                            std::uint32_t height,
                            std::uint8_t bitDepth,
                            PngColor color);

// Filters `samples` (rows top to bottom, each sample as PNG stores it: 16-bit ones big-endian)
// into `filtered` (filteredPngSize bytes).
void filterPngRows(std::span<const std::uint8_t> samples,
                   std::uint32_t height,
                   std::size_t bytesPerPixel,
                   PngRowFilter filter,
                   std::uint8_t* filtered);

// A PNG of rows filtered as pngRowFilter(bitDepth, compression) says, compressed as
// `compression` says.
Result<std::vector<std::uint8_t>> pngOfFilteredRows(std::uint32_t width,
                                                    std::uint32_t height,
                                                    std::uint8_t bitDepth,
                                                    PngColor color,
                                                    std::span<const std::uint8_t> filtered,
                                                    PngCompression compression);

// Both steps: a PNG of `samples` (as filterPngRows takes them).
Result<std::vector<std::uint8_t>> pngOfSamples(std::uint32_t width,
                                               std::uint32_t height,
                                               std::uint8_t bitDepth,
                                               PngColor color,
                                               std::span<const std::uint8_t> samples,
                                               PngCompression compression);

}  // namespace encore::image
