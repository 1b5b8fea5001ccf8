// How each PngCompression writes (speed at about the size of zlib's default, on rendered views:
// docs/benchmarks/2026-11-26-png-paeth-runs.md): Small filters 8-bit images with Paeth, after
// which runs of a repeated byte are nearly all the matches deflate finds in a rendered view, so
// runLengthZlib (one Huffman-coded block, no match search) compresses them as small as
// libdeflate's level 2 after Up (-1% to +2%) in 50-70% of the time; 16-bit images (depth's smooth
// gradients, where longer matches pay: 21% smaller) get Up and libdeflate at level 2. Fast
// filters everything with Up (the cheapest filter) and compresses runs: fastest, and 15-30%
// larger for 8-bit views.

#include "image/PngWriter.h"

#include <libdeflate.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "image/RunLengthDeflate.h"
#include "image/ScratchBuffer.h"

namespace encore::image {
namespace {

void appendBigEndian(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) {
        out.push_back(std::uint8_t(value >> shift));
    }
}

// One PNG chunk: length, type, data, CRC of type and data.
void appendChunk(std::vector<std::uint8_t>& out,
                 const char* type,
                 std::span<const std::uint8_t> data) {
    appendBigEndian(out, std::uint32_t(data.size()));
    const std::size_t typeStart = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    appendBigEndian(out, libdeflate_crc32(0, out.data() + typeStart, out.size() - typeStart));
}

constexpr int kCompressionLevel = 2;

struct CompressorFree {
    void operator()(libdeflate_compressor* compressor) const {
        libdeflate_free_compressor(compressor);
    }
};

// What encoding a PNG needs besides its input and output, kept by each thread from one image to
// the next: allocating these afresh cost nearly a third of the time of encoding a 512x512 view
// (the compressor's tables, and page faults on two fresh megabytes that were then filled anyway).
struct PngScratch {
    std::unique_ptr<libdeflate_compressor, CompressorFree> compressor;
    // At most 64 MiB kept per thread between them.
    ScratchBuffer filtered{std::size_t(32) << 20};
    ScratchBuffer compressed{std::size_t(32) << 20};
};

Error outOfMemory() {
    return makeError(ErrorCode::IoError, "PNG encoding failed (out of memory).");
}

PngScratch& threadScratch() {
    thread_local PngScratch scratch;
    return scratch;
}

// Rows with the Up filter (None for the first), each after its filter-type byte.
void filterUp(const std::uint8_t* samples,
              std::size_t rowBytes,
              std::uint32_t height,
              std::uint8_t* __restrict filtered) {
    for (std::uint32_t y = 0; y < height; ++y) {
        std::uint8_t* __restrict out = filtered + std::size_t(y) * (rowBytes + 1);
        const std::uint8_t* __restrict row = samples + std::size_t(y) * rowBytes;
        *out++ = y == 0 ? 0 : 2;
        if (y == 0) {
            std::copy(row, row + rowBytes, out);
            continue;
        }
        const std::uint8_t* __restrict above = row - rowBytes;
        // Sixteen bytes at a time: the release build's -O2 does not vectorise loops, and byte by
        // byte the filter cost a tenth of encoding a view, more or less with code placement.
        using Bytes16 = std::uint8_t __attribute__((vector_size(16)));
        std::size_t i = 0;
        for (; i + 16 <= rowBytes; i += 16) {
            Bytes16 current;
            Bytes16 previous;
            std::memcpy(&current, row + i, 16);
            std::memcpy(&previous, above + i, 16);
            const Bytes16 difference = current - previous;
            std::memcpy(out + i, &difference, 16);
        }
        for (; i < rowBytes; ++i) {
            out[i] = std::uint8_t(row[i] - above[i]);
        }
    }
}

// Rows with the Paeth filter, each after its filter-type byte; `bytesPerPixel` apart are the
// left neighbours (the row above the first is zero, as PNG defines it there).
void filterPaeth(const std::uint8_t* samples,
                 std::size_t rowBytes,
                 std::uint32_t height,
                 std::size_t bytesPerPixel,
                 std::uint8_t* __restrict filtered) {
    const auto predict = [](int left, int above, int aboveLeft) {
        const int towardsLeft = std::abs(above - aboveLeft);
        const int towardsAbove = std::abs(left - aboveLeft);
        const int towardsAboveLeft = std::abs(left + above - 2 * aboveLeft);
        if (towardsLeft <= towardsAbove && towardsLeft <= towardsAboveLeft) {
            return left;
        }
        return towardsAbove <= towardsAboveLeft ? above : aboveLeft;
    };
    const std::vector<std::uint8_t> zeros(rowBytes, 0);
    for (std::uint32_t y = 0; y < height; ++y) {
        std::uint8_t* __restrict out = filtered + std::size_t(y) * (rowBytes + 1);
        const std::uint8_t* __restrict row = samples + std::size_t(y) * rowBytes;
        const std::uint8_t* __restrict above = y == 0 ? zeros.data() : row - rowBytes;
        *out++ = 4;
        std::size_t i = 0;
        for (; i < std::min(bytesPerPixel, rowBytes); ++i) {
            out[i] = std::uint8_t(row[i] - above[i]);  // No left neighbour: the predictor is above.
        }
        // Eight bytes at a time in 16-bit lanes (the predictor's sums need nine bits): -O2 does
        // not vectorise loops, and byte by byte this filter cost as much as compressing.
        using Bytes8 = std::uint8_t __attribute__((vector_size(8)));
        using Shorts8 = std::int16_t __attribute__((vector_size(16)));
        const auto magnitude = [](Shorts8 value) { return value < 0 ? -value : value; };
        for (; i + 8 <= rowBytes; i += 8) {
            Bytes8 current;
            Bytes8 left;
            Bytes8 up;
            Bytes8 upLeft;
            std::memcpy(&current, row + i, 8);
            std::memcpy(&left, row + i - bytesPerPixel, 8);
            std::memcpy(&up, above + i, 8);
            std::memcpy(&upLeft, above + i - bytesPerPixel, 8);
            const Shorts8 a = __builtin_convertvector(left, Shorts8);
            const Shorts8 b = __builtin_convertvector(up, Shorts8);
            const Shorts8 c = __builtin_convertvector(upLeft, Shorts8);
            const Shorts8 towardsLeft = magnitude(b - c);
            const Shorts8 towardsAbove = magnitude(a - c);
            const Shorts8 towardsAboveLeft = magnitude(a + b - c - c);
            const Shorts8 predicted =
                ((towardsLeft <= towardsAbove) & (towardsLeft <= towardsAboveLeft))
                    ? a
                    : (towardsAbove <= towardsAboveLeft ? b : c);
            const Bytes8 difference = current - __builtin_convertvector(predicted, Bytes8);
            std::memcpy(out + i, &difference, 8);
        }
        for (; i < rowBytes; ++i) {
            out[i] = std::uint8_t(
                row[i] - predict(row[i - bytesPerPixel], above[i], above[i - bytesPerPixel]));
        }
    }
}

}  // namespace

PngRowFilter pngRowFilter(std::uint8_t bitDepth, PngCompression compression) {
    return compression == PngCompression::Small && bitDepth == 8 ? PngRowFilter::Paeth
                                                                 : PngRowFilter::Up;
}

std::size_t pngBytesPerPixel(std::uint8_t bitDepth, PngColor color) {
    return (color == PngColor::Rgba ? 4 : 1) * (bitDepth / 8);
}

std::size_t filteredPngSize(std::uint32_t width,
                            std::uint32_t height,
                            std::uint8_t bitDepth,
                            PngColor color) {
    return (std::size_t(width) * pngBytesPerPixel(bitDepth, color) + 1) * height;
}

void filterPngRows(std::span<const std::uint8_t> samples,
                   std::uint32_t height,
                   std::size_t bytesPerPixel,
                   PngRowFilter filter,
                   std::uint8_t* filtered) {
    const std::size_t rowBytes = samples.size() / height;
    if (filter == PngRowFilter::Paeth) {
        filterPaeth(samples.data(), rowBytes, height, bytesPerPixel, filtered);
    } else {
        filterUp(samples.data(), rowBytes, height, filtered);
    }
}

Result<std::vector<std::uint8_t>> pngOfFilteredRows(std::uint32_t width,
                                                    std::uint32_t height,
                                                    std::uint8_t bitDepth,
                                                    PngColor color,
                                                    std::span<const std::uint8_t> filtered,
                                                    PngCompression compression) {
    PngScratch& scratch = threadScratch();
    // After Paeth, and wherever Fast asks, runs are the matches there are.
    const bool runs = compression == PngCompression::Fast ||
                      pngRowFilter(bitDepth, compression) == PngRowFilter::Paeth;
    if (!runs && !scratch.compressor) {
        scratch.compressor.reset(libdeflate_alloc_compressor(kCompressionLevel));
        if (!scratch.compressor) {
            return outOfMemory();
        }
    }
    const ScratchBuffer::Use useCompressed(scratch.compressed);
    const std::size_t bound =
        runs ? runLengthZlibBound(filtered.size())
             : libdeflate_zlib_compress_bound(scratch.compressor.get(), filtered.size());
    std::uint8_t* compressed = scratch.compressed.reserve(bound);
    if (!compressed) {
        return outOfMemory();
    }
    const std::size_t compressedSize =
        runs ? runLengthZlib(filtered, compressed)
             : libdeflate_zlib_compress(scratch.compressor.get(), filtered.data(), filtered.size(),
                                        compressed, bound);
    if (compressedSize == 0) {
        return makeError(ErrorCode::IoError, "PNG encoding failed (libdeflate).");
    }

    std::vector<std::uint8_t> png;
    // Signature, IHDR, IDAT and IEND: 8 + 25 + 12 + 12 bytes around the compressed data.
    png.reserve(compressedSize + 57);
    png.insert(png.end(), {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'});
    std::vector<std::uint8_t> header;
    appendBigEndian(header, width);
    appendBigEndian(header, height);
    // Deflate, standard filters, no interlace.
    header.insert(header.end(), {bitDepth, std::uint8_t(color), 0, 0, 0});
    appendChunk(png, "IHDR", header);
    appendChunk(png, "IDAT", {compressed, compressedSize});
    appendChunk(png, "IEND", {});
    return png;
}

Result<std::vector<std::uint8_t>> pngOfSamples(std::uint32_t width,
                                               std::uint32_t height,
                                               std::uint8_t bitDepth,
                                               PngColor color,
                                               std::span<const std::uint8_t> samples,
                                               PngCompression compression) {
    PngScratch& scratch = threadScratch();
    const std::size_t filteredSize = filteredPngSize(width, height, bitDepth, color);
    const ScratchBuffer::Use useFiltered(scratch.filtered);
    std::uint8_t* filtered = scratch.filtered.reserve(filteredSize);
    if (!filtered) {
        return outOfMemory();
    }
    filterPngRows(samples, height, pngBytesPerPixel(bitDepth, color),
                  pngRowFilter(bitDepth, compression), filtered);
    return pngOfFilteredRows(width, height, bitDepth, color, {filtered, filteredSize}, compression);
}

}  // namespace encore::image
