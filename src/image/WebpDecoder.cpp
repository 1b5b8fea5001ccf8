// WebP decoding with libwebp (EXT_texture_webp): lossy and lossless still images, with or
// without alpha, straight into an RGBA buffer of the size the header declares. Animated WebP
// files are refused: a texture is one picture, and the extension's fallback image is drawn.

#include <webp/decode.h>

#include <string>

#include "image/ImageDecoders.h"

namespace encore::image {
namespace {

std::string statusName(VP8StatusCode status) {
    switch (status) {
        case VP8_STATUS_OUT_OF_MEMORY:
            return "out of memory";
        case VP8_STATUS_INVALID_PARAM:
            return "invalid parameter";
        case VP8_STATUS_BITSTREAM_ERROR:
            return "bitstream error";
        case VP8_STATUS_UNSUPPORTED_FEATURE:
            return "unsupported feature";
        case VP8_STATUS_NOT_ENOUGH_DATA:
            return "the data is cut short";
        default:
            return "status " + std::to_string(int(status));
    }
}

}  // namespace

bool isWebp(std::span<const std::uint8_t> encoded) {
    // A RIFF container ("RIFF", its length, then the form type "WEBP").
    return encoded.size() >= 12 && encoded[0] == 'R' && encoded[1] == 'I' && encoded[2] == 'F' &&
           encoded[3] == 'F' && encoded[8] == 'W' && encoded[9] == 'E' && encoded[10] == 'B' &&
           encoded[11] == 'P';
}

Result<ImageRgba8> decodeWebp(std::span<const std::uint8_t> encoded) {
    WebPBitstreamFeatures features;
    const VP8StatusCode status = WebPGetFeatures(encoded.data(), encoded.size(), &features);
    if (status != VP8_STATUS_OK) {
        return makeError(ErrorCode::InvalidFormat,
                         "Image data is not a decodable WebP image (" + statusName(status) + ").");
    }
    if (features.has_animation) {
        return makeError(ErrorCode::Unsupported,
                         "The WebP image is animated; Encore decodes still WebP images only.");
    }
    if (features.width <= 0 || features.height <= 0) {
        return makeError(ErrorCode::InvalidFormat, "The WebP image declares no size.");
    }
    ENCORE_TRY(checkDecodable(
        {static_cast<std::uint32_t>(features.width), static_cast<std::uint32_t>(features.height)}));
    ImageRgba8 image;
    image.width = static_cast<std::uint32_t>(features.width);
    image.height = static_cast<std::uint32_t>(features.height);
    const std::size_t stride = std::size_t(image.width) * 4;
    image.pixels.resize(stride * image.height);
    // Opaque images get alpha 255, as the other decoders give them.
    if (!WebPDecodeRGBAInto(encoded.data(), encoded.size(), image.pixels.data(),
                            image.pixels.size(), static_cast<int>(stride))) {
        return makeError(ErrorCode::InvalidFormat,
                         "WebP decoding failed (the image data is corrupt or cut short).");
    }
    return image;
}

}  // namespace encore::image
