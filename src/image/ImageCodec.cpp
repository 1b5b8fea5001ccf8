#include "encore/image/ImageCodec.h"

#include <stb_image.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "core/FileIO.h"
#include "image/ImageDecoders.h"
#include "image/PngWriter.h"

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
    return pngOfSamples(image.width, image.height, 8, PngColor::Rgba, image.pixels, compression);
}

Result<std::vector<std::uint8_t>> encodePng16(const ImageGray16& image,
                                              PngCompression compression) {
    ENCORE_TRY(checkEncodable(image.width, image.height, image.pixels.size(), 1));
    std::vector<std::uint8_t> samples(image.pixels.size() * 2);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        samples[2 * i] = std::uint8_t(image.pixels[i] >> 8);  // PNG stores 16-bit big-endian.
        samples[2 * i + 1] = std::uint8_t(image.pixels[i] & 0xff);
    }
    return pngOfSamples(image.width, image.height, 16, PngColor::Gray, samples, compression);
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
