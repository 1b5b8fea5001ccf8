#include "encore/image/ImageCodec.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <memory>
#include <string>

#include "encore/core/FileIO.h"

namespace encore::image {
namespace {

struct StbiFree {
    void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

}  // namespace

Result<ImageRgba8> decodeImage(std::span<const std::uint8_t> encoded) {
    if (encoded.empty() || encoded.size() > static_cast<std::size_t>(INT32_MAX)) {
        return makeError(ErrorCode::InvalidFormat,
                         "Image data is empty or too large (" + std::to_string(encoded.size()) +
                             " bytes).");
    }
    const int length = static_cast<int>(encoded.size());
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(encoded.data(), length, &width, &height, &channels)) {
        return makeError(ErrorCode::InvalidFormat,
                         std::string("Image data is not a decodable PNG or JPEG (") +
                             stbi_failure_reason() + ").");
    }
    if (width <= 0 || height <= 0 || static_cast<std::uint32_t>(width) > kMaxImageDimension ||
        static_cast<std::uint32_t>(height) > kMaxImageDimension) {
        return makeError(ErrorCode::LimitExceeded,
                         "Image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is outside 1.." + std::to_string(kMaxImageDimension) + ".");
    }
    if (std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels) {
        return makeError(ErrorCode::LimitExceeded,
                         "Image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " has more than the " + std::to_string(kMaxImagePixels) +
                             " pixels Encore decodes.");
    }
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

Result<std::vector<std::uint8_t>> encodePng(const ImageRgba8& image) {
    if (image.width == 0 || image.height == 0 ||
        image.pixels.size() != std::size_t(image.width) * image.height * 4) {
        return makeError(ErrorCode::InvalidArgument, "Cannot encode an empty or inconsistent image (" +
                                                         std::to_string(image.width) + "x" +
                                                         std::to_string(image.height) + ").");
    }
    std::vector<std::uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        out->insert(out->end(), bytes, bytes + size);
    };
    const int ok = stbi_write_png_to_func(append, &png, static_cast<int>(image.width),
                                          static_cast<int>(image.height), 4, image.pixels.data(),
                                          static_cast<int>(image.width * 4));
    if (!ok) {
        return makeError(ErrorCode::IoError, "PNG encoding failed.");
    }
    return png;
}

Result<void> writePng(const std::filesystem::path& path, const ImageRgba8& image) {
    auto png = encodePng(image);
    if (!png) {
        return png.error().withContext("Writing '" + path.string() + "'");
    }
    return writeFile(path, *png);
}

Result<ImageRgba8> readImage(const std::filesystem::path& path) {
    auto bytes = readFile(path);
    if (!bytes) {
        return bytes.error();
    }
    auto image = decodeImage(*bytes);
    if (!image) {
        return image.error().withContext("'" + path.string() + "'");
    }
    return image;
}

}  // namespace encore::image
