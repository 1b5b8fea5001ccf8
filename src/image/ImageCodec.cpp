#include "encore/image/ImageCodec.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <memory>
#include <string>

#include "encore/core/FileIO.h"

namespace encore::image {
namespace {

struct StbiFree {
    void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

// stb_image sizes its buffer for compressed PNG data from each chunk's declared length before
// it reads the chunk, so a corrupt length allocates gigabytes (a fuzzer finding: an IDAT
// declaring 1.4 GB in a 42 kB file). Every chunk must fit in the bytes that are there.
Result<void> checkPngChunks(std::span<const std::uint8_t> encoded) {
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (encoded.size() < sizeof(kSignature) ||
        !std::equal(std::begin(kSignature), std::end(kSignature), encoded.begin())) {
        return {};  // Not a PNG.
    }
    std::size_t offset = sizeof(kSignature);
    while (encoded.size() - offset >= 12) {
        const std::uint8_t* chunk = encoded.data() + offset;
        const std::uint64_t length = (std::uint64_t(chunk[0]) << 24) | (std::uint64_t(chunk[1]) << 16) |
                                     (std::uint64_t(chunk[2]) << 8) | std::uint64_t(chunk[3]);
        const std::string type(reinterpret_cast<const char*>(chunk + 4), 4);
        const std::uint64_t remaining = encoded.size() - offset - 12;
        if (length > remaining) {
            return makeError(ErrorCode::InvalidFormat,
                             "PNG chunk at byte " + std::to_string(offset) + " declares " +
                                 std::to_string(length) + " bytes, but only " +
                                 std::to_string(remaining) + " follow.");
        }
        if (type == "IEND") {
            break;
        }
        offset += 12 + std::size_t(length);
    }
    return {};
}

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
    const int bytesPerChannel = stbi_is_16_bit_from_memory(encoded.data(), length) ? 2 : 1;
    const std::uint64_t decodedBytes = std::uint64_t(width) * std::uint64_t(height) *
                                       std::uint64_t(std::max(channels, 4)) *
                                       std::uint64_t(bytesPerChannel);
    if (decodedBytes > kMaxDecodedImageBytes) {
        return makeError(ErrorCode::LimitExceeded,
                         "Image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " with " + std::to_string(8 * bytesPerChannel) +
                             "-bit channels needs " + std::to_string(decodedBytes >> 20) +
                             " MiB to decode, more than the " +
                             std::to_string(kMaxDecodedImageBytes >> 20) + " MiB Encore allows.");
    }
    if (auto chunks = checkPngChunks(encoded); !chunks) {
        return chunks.error();
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
