#include "encore/image/ImageCodec.h"

#include <libdeflate.h>
#include <stb_image.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "core/FileIO.h"
#include "image/ImageDecoders.h"
#include "image/RunLengthDeflate.h"
#include "image/ScratchBuffer.h"

namespace encore::image {
namespace {

struct StbiFree {
    void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

Result<void> checkDecodable(const ImageHeader& header) {
    const std::string size = std::to_string(header.width) + "x" + std::to_string(header.height);
    if (header.width == 0 || header.height == 0 || header.width > kMaxImageDimension ||
        header.height > kMaxImageDimension) {
        return makeError(ErrorCode::LimitExceeded, "Image size " + size + " is outside 1.." +
                                                       std::to_string(kMaxImageDimension) + ".");
    }
    if (std::uint64_t(header.width) * header.height > kMaxImagePixels) {
        return makeError(ErrorCode::LimitExceeded, "Image size " + size + " has more than the " +
                                                       std::to_string(kMaxImagePixels) +
                                                       " pixels Encore decodes.");
    }
    // Four channels: grey, grey-alpha and RGB become RGBA.
    const std::uint64_t decodedBytes =
        std::uint64_t(header.width) * header.height * 4 * (header.bitsPerChannel / 8);
    if (decodedBytes > kMaxDecodedImageBytes) {
        return makeError(ErrorCode::LimitExceeded,
                         "Image size " + size + " with " + std::to_string(header.bitsPerChannel) +
                             "-bit channels needs " + std::to_string(decodedBytes >> 20) +
                             " MiB to decode, more than the " +
                             std::to_string(kMaxDecodedImageBytes >> 20) + " MiB Encore allows.");
    }
    return {};
}

Result<ImageRgba8> decodeWithStb(std::span<const std::uint8_t> encoded) {
    const int length = static_cast<int>(encoded.size());
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(encoded.data(), length, &width, &height, &channels)) {
        return makeError(ErrorCode::InvalidFormat,
                         std::string("Image data is not a decodable PNG or JPEG (") +
                             stbi_failure_reason() + ").");
    }
    const bool sixteenBit = stbi_is_16_bit_from_memory(encoded.data(), length);
    ENCORE_TRY(
        checkDecodable({static_cast<std::uint32_t>(std::max(width, 0)),
                        static_cast<std::uint32_t>(std::max(height, 0)), sixteenBit ? 16u : 8u}));
    std::unique_ptr<stbi_uc, StbiFree> pixels(
        stbi_load_from_memory(encoded.data(), length, &width, &height, &channels, 4));
    if (!pixels) {
        return makeError(ErrorCode::InvalidFormat,
                         std::string("Image decoding failed (") + stbi_failure_reason() + ").");
    }
    ImageRgba8 image;
    image.width = static_cast<std::uint32_t>(width);
    image.height = static_cast<std::uint32_t>(height);
    image.pixels.assign(pixels.get(), pixels.get() + std::size_t(width) * std::size_t(height) * 4);
    return image;
}

Result<ImageRgba8> decodeImage(std::span<const std::uint8_t> encoded) {
    if (encoded.empty() || encoded.size() > static_cast<std::size_t>(INT32_MAX)) {
        return makeError(ErrorCode::InvalidFormat, "Image data is empty or too large (" +
                                                       std::to_string(encoded.size()) + " bytes).");
    }
    if (isPng(encoded)) {
        return decodePng(encoded);
    }
    if (isJpeg(encoded)) {
        return decodeJpeg(encoded);
    }
    if (isWebp(encoded)) {
        return decodeWebp(encoded);
    }
    return decodeWithStb(encoded);
}

namespace {

// An image to encode has pixels, and as many samples as its size says.
Result<void> checkEncodable(std::uint32_t width,
                            std::uint32_t height,
                            std::size_t samples,
                            std::size_t samplesPerPixel) {
    if (width == 0 || height == 0 || samples != std::size_t(width) * height * samplesPerPixel) {
        return makeError(ErrorCode::InvalidArgument,
                         "Cannot encode an empty or inconsistent image (" + std::to_string(width) +
                             "x" + std::to_string(height) + ").");
    }
    return {};
}

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

enum class PngColor : std::uint8_t { Gray = 0, Rgba = 6 };

// What encoding a PNG needs besides its input and output, kept by each thread from one image to
// the next: allocating these afresh cost nearly a third of the time of encoding a 512x512 view
// (the compressor's tables, and page faults on two fresh megabytes that were then filled anyway).
struct PngScratch {
    std::unique_ptr<libdeflate_compressor, CompressorFree> compressor;
    // At most 64 MiB kept per thread between them.
    ScratchBuffer filtered{std::size_t(32) << 20};
    ScratchBuffer compressed{std::size_t(32) << 20};
};

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

// A PNG of `samples` (rows top to bottom, each sample as PNG stores it: 16-bit ones big-endian).
// Speed at about the size of zlib's default (docs/benchmarks/2026-11-26-png-paeth-runs.md):
// PngCompression::Small filters 8-bit images with Paeth, after which runs of a repeated byte are
// nearly all the matches deflate finds in a rendered view, so runLengthZlib (one Huffman-coded
// block, no match search) compresses them as small as libdeflate's level 2 after Up (-1% to
// +2%) in 50-70% of the time; 16-bit images (depth's smooth gradients, where longer matches pay:
// 21% smaller) get Up and libdeflate at level 2. PngCompression::Fast filters everything with
// Up (the cheapest filter) and compresses runs: fastest, and 15-30% larger for 8-bit views.
Result<std::vector<std::uint8_t>> writePngStream(std::uint32_t width,
                                                 std::uint32_t height,
                                                 std::uint8_t bitDepth,
                                                 PngColor color,
                                                 std::span<const std::uint8_t> samples,
                                                 PngCompression compression) {
    thread_local PngScratch scratch;
    const auto outOfMemory = [] {
        return makeError(ErrorCode::IoError, "PNG encoding failed (out of memory).");
    };
    const bool paeth = compression == PngCompression::Small && bitDepth == 8;
    const bool runs =
        compression == PngCompression::Fast || paeth;  // runLengthZlib, else libdeflate.
    const std::size_t rowBytes = samples.size() / height;
    const std::size_t filteredSize = (rowBytes + 1) * height;
    const ScratchBuffer::Use useFiltered(scratch.filtered);
    const ScratchBuffer::Use useCompressed(scratch.compressed);
    std::uint8_t* filtered = scratch.filtered.reserve(filteredSize);
    if (!runs && !scratch.compressor) {
        scratch.compressor.reset(libdeflate_alloc_compressor(kCompressionLevel));
    }
    if (!filtered || (!runs && !scratch.compressor)) {
        return outOfMemory();
    }
    if (paeth) {
        const std::size_t bytesPerPixel = color == PngColor::Rgba ? 4 : 1;
        filterPaeth(samples.data(), rowBytes, height, bytesPerPixel, filtered);
    } else {
        filterUp(samples.data(), rowBytes, height, filtered);
    }
    const std::size_t bound =
        runs ? runLengthZlibBound(filteredSize)
             : libdeflate_zlib_compress_bound(scratch.compressor.get(), filteredSize);
    std::uint8_t* compressed = scratch.compressed.reserve(bound);
    if (!compressed) {
        return outOfMemory();
    }
    const std::size_t compressedSize =
        runs ? runLengthZlib({filtered, filteredSize}, compressed)
             : libdeflate_zlib_compress(scratch.compressor.get(), filtered, filteredSize,
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

}  // namespace

std::optional<PngCompression> pngCompressionFromName(std::string_view name) {
    if (name == "small") {
        return PngCompression::Small;
    }
    if (name == "fast") {
        return PngCompression::Fast;
    }
    return std::nullopt;
}

Result<std::vector<std::uint8_t>> encodePng(const ImageRgba8& image, PngCompression compression) {
    ENCORE_TRY(checkEncodable(image.width, image.height, image.pixels.size(), 4));
    return writePngStream(image.width, image.height, 8, PngColor::Rgba, image.pixels, compression);
}

Result<std::vector<std::uint8_t>> encodePng16(const ImageGray16& image,
                                              PngCompression compression) {
    ENCORE_TRY(checkEncodable(image.width, image.height, image.pixels.size(), 1));
    std::vector<std::uint8_t> samples(image.pixels.size() * 2);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        samples[2 * i] = std::uint8_t(image.pixels[i] >> 8);  // PNG stores 16-bit big-endian.
        samples[2 * i + 1] = std::uint8_t(image.pixels[i] & 0xff);
    }
    return writePngStream(image.width, image.height, 16, PngColor::Gray, samples, compression);
}

Result<void> writePng(const std::filesystem::path& path, const ImageRgba8& image) {
    auto png = encodePng(image);
    if (!png) {
        return png.error().withContext("Writing '" + path.string() + "'");
    }
    return writeFile(path, *png);
}

Result<ImageRgba8> readImage(const std::filesystem::path& path) {
    ENCORE_TRY_ASSIGN(auto bytes, readFile(path));
    auto image = decodeImage(bytes);
    if (!image) {
        return image.error().withContext("'" + path.string() + "'");
    }
    return image;
}

}  // namespace encore::image
