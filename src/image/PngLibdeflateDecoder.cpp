// The PNGs that glTF textures almost always are (8 bits per sample, not interlaced), decoded with
// libdeflate's inflate, which is about twice as fast as zlib's that libspng uses: loading
// Avocado (three 2048x2048 PNG textures) took 142 ms of CPU with libspng, 98 ms with this and
// a buffer kept per thread (docs/benchmarks/2026-11-24-lavapipe-batch-load.md). The rows are
// unfiltered and expanded to RGBA8 as libspng does (palettes and tRNS colour keys applied), one
// row at a time while it is still in cache. Anything else, and any file this path finds wrong,
// goes to libspng, so its checks and error messages stay the only ones.

#include <libdeflate.h>

#include <cstring>
#include <memory>
#include <vector>

#include "image/ImageDecoders.h"
#include "image/ScratchBuffer.h"

namespace encore::image {
namespace {

struct DecompressorFree {
    void operator()(libdeflate_decompressor* decompressor) const {
        libdeflate_free_decompressor(decompressor);
    }
};

// What the chunks before the pixels say, and the pixels' zlib stream.
struct PngChunks {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint8_t bitDepth = 0;
    std::uint8_t colorType = 0;
    bool interlaced = false;
    std::span<const std::uint8_t> palette;       // PLTE: RGB triples.
    std::span<const std::uint8_t> transparency;  // tRNS.
    // The IDAT chunks' data, as one span when there is one chunk, else joined in `joined`.
    std::span<const std::uint8_t> compressed;
    std::vector<std::uint8_t> joined;
};

// Reads the chunks. False on anything this path does not take or finds odd (a chunk that does
// not fit included): the caller then uses libspng.
bool readChunks(std::span<const std::uint8_t> encoded, PngChunks& chunks) {
    std::size_t idatChunks = 0;
    bool sawHeader = false;
    bool usable = true;
    const Result<void> walked = forEachPngChunk(encoded, [&](const PngChunk& chunk) {
        const std::span<const std::uint8_t> data = chunk.data;
        if (chunk.type == "IHDR") {
            // Compression and filter method 0 are the only ones PNG defines.
            if (sawHeader || chunk.offset != 8 || data.size() != 13 || data[10] != 0 ||
                data[11] != 0 || data[12] > 1) {
                usable = false;
                return false;
            }
            sawHeader = true;
            chunks.width = pngUint32(data.data());
            chunks.height = pngUint32(data.data() + 4);
            chunks.bitDepth = data[8];
            chunks.colorType = data[9];
            chunks.interlaced = data[12] == 1;
        } else if (chunk.type == "PLTE") {
            chunks.palette = data;
        } else if (chunk.type == "tRNS") {
            chunks.transparency = data;
        } else if (chunk.type == "IDAT") {
            if (++idatChunks == 1) {
                chunks.compressed = data;
            } else {
                if (idatChunks == 2) {
                    chunks.joined.assign(chunks.compressed.begin(), chunks.compressed.end());
                }
                chunks.joined.insert(chunks.joined.end(), data.begin(), data.end());
            }
        }
        return true;
    });
    if (idatChunks > 1) {
        chunks.compressed = chunks.joined;
    }
    return walked.ok() && usable && sawHeader && idatChunks > 0;
}

std::size_t channelsOf(std::uint8_t colorType) {
    switch (colorType) {
        case 0:
        case 3:
            return 1;
        case 4:
            return 2;
        case 2:
            return 3;
        case 6:
            return 4;
        default:
            return 0;
    }
}

// Undoes the row's filter in place; `above` is the previous unfiltered row (zeros for the
// first). False for a filter type PNG does not define.
bool unfilterRow(std::uint8_t filter,
                 std::uint8_t* row,
                 const std::uint8_t* above,
                 std::size_t rowBytes,
                 std::size_t bytesPerPixel) {
    switch (filter) {
        case 0:
            return true;
        case 1:
            for (std::size_t i = bytesPerPixel; i < rowBytes; ++i) {
                row[i] = std::uint8_t(row[i] + row[i - bytesPerPixel]);
            }
            return true;
        case 2:
            for (std::size_t i = 0; i < rowBytes; ++i) {
                row[i] = std::uint8_t(row[i] + above[i]);
            }
            return true;
        case 3:
            for (std::size_t i = 0; i < bytesPerPixel; ++i) {
                row[i] = std::uint8_t(row[i] + (above[i] >> 1));
            }
            for (std::size_t i = bytesPerPixel; i < rowBytes; ++i) {
                row[i] = std::uint8_t(row[i] + ((row[i - bytesPerPixel] + above[i]) >> 1));
            }
            return true;
        case 4:
            for (std::size_t i = 0; i < bytesPerPixel; ++i) {
                row[i] = std::uint8_t(row[i] + above[i]);  // Paeth of (0, above, 0).
            }
            for (std::size_t i = bytesPerPixel; i < rowBytes; ++i) {
                const int left = row[i - bytesPerPixel];
                const int up = above[i];
                const int upLeft = above[i - bytesPerPixel];
                const int toLeft = up - upLeft;      // |p - left| with p = left + up - upLeft.
                const int toUp = left - upLeft;      // |p - up|.
                const int toUpLeft = toLeft + toUp;  // |p - upLeft|.
                const int a = toLeft < 0 ? -toLeft : toLeft;
                const int b = toUp < 0 ? -toUp : toUp;
                const int c = toUpLeft < 0 ? -toUpLeft : toUpLeft;
                const int predicted = (a <= b && a <= c) ? left : (b <= c ? up : upLeft);
                row[i] = std::uint8_t(row[i] + predicted);
            }
            return true;
        default:
            return false;
    }
}

// One unfiltered row to RGBA8. False for a palette index past the palette.
bool expandRow(const PngChunks& chunks, const std::uint8_t* row, std::uint8_t* out) {
    const std::uint32_t width = chunks.width;
    const std::span<const std::uint8_t> key = chunks.transparency;
    switch (chunks.colorType) {
        case 0: {
            // A tRNS key is a 16-bit sample; at 8 bits only values up to 255 can match.
            const int transparent = key.size() >= 2 ? int(std::uint32_t(key[0]) << 8 | key[1]) : -1;
            for (std::uint32_t x = 0; x < width; ++x, out += 4) {
                const std::uint8_t grey = row[x];
                out[0] = out[1] = out[2] = grey;
                out[3] = grey == transparent ? 0 : 255;
            }
            return true;
        }
        case 2: {
            const bool keyed = key.size() >= 6;
            const int red = keyed ? int(std::uint32_t(key[0]) << 8 | key[1]) : -1;
            const int green = keyed ? int(std::uint32_t(key[2]) << 8 | key[3]) : -1;
            const int blue = keyed ? int(std::uint32_t(key[4]) << 8 | key[5]) : -1;
            for (std::uint32_t x = 0; x < width; ++x, out += 4, row += 3) {
                out[0] = row[0];
                out[1] = row[1];
                out[2] = row[2];
                out[3] = (row[0] == red && row[1] == green && row[2] == blue) ? 0 : 255;
            }
            return true;
        }
        case 3: {
            const std::size_t colours = chunks.palette.size() / 3;
            for (std::uint32_t x = 0; x < width; ++x, out += 4) {
                const std::size_t index = row[x];
                if (index >= colours) {
                    return false;
                }
                std::memcpy(out, &chunks.palette[index * 3], 3);
                out[3] = index < key.size() ? key[index] : 255;
            }
            return true;
        }
        case 4:
            for (std::uint32_t x = 0; x < width; ++x, out += 4, row += 2) {
                out[0] = out[1] = out[2] = row[0];
                out[3] = row[1];
            }
            return true;
        case 6:
            std::memcpy(out, row, std::size_t(width) * 4);
            return true;
        default:
            return false;
    }
}

}  // namespace

std::optional<ImageRgba8> decodePngWithLibdeflate(std::span<const std::uint8_t> encoded) {
    PngChunks chunks;
    if (!readChunks(encoded, chunks) || chunks.bitDepth != 8 || chunks.interlaced ||
        chunks.width == 0 || chunks.height == 0) {
        return std::nullopt;
    }
    const std::size_t channels = channelsOf(chunks.colorType);
    if (channels == 0 || (chunks.colorType == 3 && chunks.palette.empty()) ||
        !checkDecodable({chunks.width, chunks.height, 8}).ok()) {
        return std::nullopt;
    }
    const std::size_t rowBytes = std::size_t(chunks.width) * channels;
    const std::size_t filteredBytes = (rowBytes + 1) * chunks.height;

    // Kept by each thread for the next image: fresh megabytes cost as much in page faults as
    // the inflate itself.
    thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> decompressor(
        libdeflate_alloc_decompressor());
    thread_local ScratchBuffer scratch(std::size_t(64) << 20);
    const ScratchBuffer::Use useScratch(scratch);
    // Not zeroed: the inflate writes every byte or the decode is abandoned.
    std::uint8_t* const filtered = scratch.reserve(filteredBytes);
    if (!decompressor || !filtered) {
        return std::nullopt;
    }
    std::size_t inflated = 0;
    // The whole stream must inflate to exactly the rows: short data, trailing data and a bad
    // Adler-32 (which libspng is told to ignore, as stb_image did) all go to libspng.
    if (libdeflate_zlib_decompress(decompressor.get(), chunks.compressed.data(),
                                   chunks.compressed.size(), filtered, filteredBytes,
                                   &inflated) != LIBDEFLATE_SUCCESS ||
        inflated != filteredBytes) {
        return std::nullopt;
    }

    ImageRgba8 image;
    image.width = chunks.width;
    image.height = chunks.height;
    image.pixels.resize(std::size_t(chunks.width) * chunks.height * 4);
    const std::vector<std::uint8_t> zeros(rowBytes, 0);
    const std::uint8_t* above = zeros.data();
    for (std::uint32_t y = 0; y < chunks.height; ++y) {
        std::uint8_t* line = filtered + std::size_t(y) * (rowBytes + 1);
        std::uint8_t* row = line + 1;
        if (!unfilterRow(line[0], row, above, rowBytes, channels) ||
            !expandRow(chunks, row, &image.pixels[std::size_t(y) * chunks.width * 4])) {
            return std::nullopt;
        }
        above = row;
    }
    return image;
}

}  // namespace encore::image
