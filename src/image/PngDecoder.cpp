// PNG decoding with libspng: on 2048x2048 textures it takes about 80% of stb_image's time
// (zlib's inflate against stb's) and its RGBA8 output equals stb's byte for byte for every
// colour type and bit depth (16-bit samples keep their high byte, low bit depths are scaled,
// palettes and tRNS colour keys expanded), which the unit tests check against stb itself.
// 8-bit non-interlaced PNGs, nearly all textures, go through decodePngWithLibdeflate first
// (faster again, same pixels); libspng takes the rest and everything that path refuses.

#include <spng.h>

#include <algorithm>
#include <memory>
#include <string>

#include "image/ImageDecoders.h"

namespace encore::image {
namespace {

struct SpngContextFree {
    void operator()(spng_ctx* context) const { spng_ctx_free(context); }
};

Error spngError(const char* what, int code) {
    return makeError(ErrorCode::InvalidFormat,
                     std::string(what) + " (" + spng_strerror(code) + ").");
}

}  // namespace

Result<void> forEachPngChunk(std::span<const std::uint8_t> encoded,
                             const std::function<bool(const PngChunk&)>& visit) {
    std::size_t offset = 8;  // The signature, which isPng has checked.
    while (encoded.size() - offset >= 12) {
        const std::uint8_t* header = encoded.data() + offset;
        const std::uint64_t length = pngUint32(header);
        const std::uint64_t remaining = encoded.size() - offset - 12;
        if (length > remaining) {
            return makeError(ErrorCode::InvalidFormat,
                             "PNG chunk at byte " + std::to_string(offset) + " declares " +
                                 std::to_string(length) + " bytes, but only " +
                                 std::to_string(remaining) + " follow.");
        }
        const PngChunk chunk{std::string_view(reinterpret_cast<const char*>(header + 4), 4),
                             {header + 8, std::size_t(length)},
                             offset};
        if (!visit(chunk) || chunk.type == "IEND") {
            break;
        }
        offset += 12 + std::size_t(length);
    }
    return {};
}

bool isPng(std::span<const std::uint8_t> encoded) {
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return encoded.size() >= sizeof(kSignature) &&
           std::equal(std::begin(kSignature), std::end(kSignature), encoded.begin());
}

Result<ImageRgba8> decodePng(std::span<const std::uint8_t> encoded) {
    if (std::optional<ImageRgba8> image = decodePngWithLibdeflate(encoded)) {
        return std::move(*image);
    }
    // What that path refused. A chunk that does not fit is an error before libspng sees it.
    ENCORE_TRY(forEachPngChunk(encoded, [](const PngChunk&) { return true; }));
    // stb_image checked neither the chunks' CRCs nor the zlib stream's Adler-32: files that
    // decoded before still decode.
    std::unique_ptr<spng_ctx, SpngContextFree> context(spng_ctx_new(SPNG_CTX_IGNORE_ADLER32));
    if (!context) {
        return makeError(ErrorCode::LimitExceeded, "PNG decoding failed (out of memory).");
    }
    spng_set_crc_action(context.get(), SPNG_CRC_USE, SPNG_CRC_USE);
    // spng_set_png_buffer only reads the buffer; its pointer parameter is not const.
    if (const int code = spng_set_png_buffer(
            context.get(), const_cast<std::uint8_t*>(encoded.data()), encoded.size())) {
        return spngError("Image data is not a decodable PNG", code);
    }
    spng_ihdr ihdr{};
    if (const int code = spng_get_ihdr(context.get(), &ihdr)) {
        return spngError("Image data is not a decodable PNG", code);
    }
    ENCORE_TRY(checkDecodable({ihdr.width, ihdr.height, ihdr.bit_depth == 16 ? 16u : 8u}));

    std::size_t bytes = 0;
    if (const int code = spng_decoded_image_size(context.get(), SPNG_FMT_RGBA8, &bytes)) {
        return spngError("PNG decoding failed", code);
    }
    ImageRgba8 image;
    image.width = ihdr.width;
    image.height = ihdr.height;
    image.pixels.resize(bytes);
    if (const int code = spng_decode_image(context.get(), image.pixels.data(), bytes,
                                           SPNG_FMT_RGBA8, SPNG_DECODE_TRNS)) {
        return spngError("PNG decoding failed", code);
    }
    return image;
}

}  // namespace encore::image
