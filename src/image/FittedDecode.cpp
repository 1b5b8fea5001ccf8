#include "image/FittedDecode.h"

#include <algorithm>

#include "image/ImageDecoders.h"

namespace encore::image {
namespace {

// The size a JPEG's header declares; nothing for other formats or a header that does not parse.
ImageSize jpegSourceSize(std::span<const std::uint8_t> encoded) {
    // Markers from SOI: each FFxx with a 16-bit length, up to the first start of frame
    // (C0..CF but C4, C8 and CC), whose payload holds the height then the width.
    std::size_t at = 2;
    while (at + 4 <= encoded.size()) {
        if (encoded[at] != 0xff) {
            return {};
        }
        const std::uint8_t marker = encoded[at + 1];
        if (marker == 0xff) {
            ++at;  // Fill bytes.
            continue;
        }
        const std::size_t length = std::size_t(encoded[at + 2]) << 8 | encoded[at + 3];
        const bool startOfFrame =
            marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (startOfFrame && at + 9 <= encoded.size()) {
            return {std::uint32_t(encoded[at + 7]) << 8 | encoded[at + 8],
                    std::uint32_t(encoded[at + 5]) << 8 | encoded[at + 6]};
        }
        at += 2 + length;
    }
    return {};
}

}  // namespace

Result<FittedDecode> decodeImageWithin(std::span<const std::uint8_t> encoded,
                                       std::uint32_t maxDimension,
                                       PixelEncoding encoding) {
    FittedDecode fitted;
    if (maxDimension > 0 && isPng(encoded) && encoded.size() >= 25 &&
        !checkDecodable(
            {pngUint32(&encoded[16]), pngUint32(&encoded[20]), encoded[24] == 16 ? 16u : 8u})) {
        // Too large to decode whole (IHDR's size, right after the signature): row by row.
        return decodeLargePngWithin(encoded, maxDimension, encoding);
    }
    if (maxDimension > 0 && isJpeg(encoded)) {
        ENCORE_TRY_ASSIGN(fitted.image, decodeJpeg(encoded, maxDimension));
        fitted.source = jpegSourceSize(encoded);
    } else {
        ENCORE_TRY_ASSIGN(fitted.image, decodeImage(encoded));
    }
    const ImageSize decoded{fitted.image.width, fitted.image.height};
    if (fitted.source.width < decoded.width || fitted.source.height < decoded.height) {
        fitted.source = decoded;
    }
    if (maxDimension == 0) {
        return fitted;
    }
    ImageSize target = fitWithin(fitted.source, maxDimension);
    target = {std::min(target.width, decoded.width), std::min(target.height, decoded.height)};
    if (target != decoded) {
        fitted.image.pixels = downscaleRgba8(fitted.image.pixels, decoded, target, encoding);
        fitted.image.width = target.width;
        fitted.image.height = target.height;
    }
    return fitted;
}

}  // namespace encore::image
