#include "encore/image/HdrImage.h"

// stb's implementation lives in Debian's libstb (linked through pkg-config), so this file
// includes only the declarations, like ImageCodec.cpp.
#include <stb_image.h>

#include <algorithm>
#include <memory>
#include <string>

#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"

namespace encore::image {
namespace {

struct StbiFreeFloat {
    void operator()(float* pixels) const { stbi_image_free(pixels); }
};

std::string sizeText(long long width, long long height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// stb's RLE reader loops forever on a dump of length 0, which is also what it reads past the
// end of truncated data (stbi__get8 returns 0 there), so the scanline structure is walked here
// first. Only what would hang stb is refused; other corruption is left to stb's own errors.
Result<void> checkRunLengthScanlines(std::span<const std::uint8_t> data,
                                     std::uint32_t width,
                                     std::uint32_t height) {
    std::size_t position = 0;
    auto nextLine = [&] {
        std::size_t start = position;
        while (position < data.size() && data[position] != '\n') {
            ++position;
        }
        const std::size_t length = position - start;
        position = std::min(position + 1, data.size());
        return length;
    };
    nextLine();  // The signature.
    while (position < data.size() && nextLine() != 0) {
    }
    nextLine();  // The resolution, "-Y height +X width".
    // stb reads flat pixels (bounded loops) for these widths and for scanlines without the
    // RLE marker, and keeps reading flat from the first such scanline on.
    if (width < 8 || width >= 32768) {
        return {};
    }
    for (std::uint32_t row = 0; row < height; ++row) {
        if (position + 4 > data.size()) {
            return makeError(ErrorCode::InvalidFormat,
                             "The Radiance HDR pixels are truncated (scanline " +
                                 std::to_string(row) + " of " + std::to_string(height) +
                                 " is missing).");
        }
        if (data[position] != 2 || data[position + 1] != 2 || (data[position + 2] & 0x80)) {
            return {};
        }
        position += 4;
        for (int component = 0; component < 4; ++component) {
            std::uint32_t filled = 0;
            while (filled < width) {
                if (position >= data.size()) {
                    return makeError(ErrorCode::InvalidFormat,
                                     "The Radiance HDR pixels are truncated (in scanline " +
                                         std::to_string(row) + " of " + std::to_string(height) +
                                         ").");
                }
                const std::uint32_t count = data[position++];
                if (count == 0) {
                    return makeError(ErrorCode::InvalidFormat, "The Radiance HDR scanline " +
                                                                   std::to_string(row) +
                                                                   " has a run of length 0.");
                }
                const std::uint32_t length = count > 128 ? count - 128 : count;
                if (length > width - filled) {
                    return {};  // stb reports "bad RLE data".
                }
                position += count > 128 ? 1 : count;
                filled += length;
            }
            // stb would read zeros for the missing bytes; refuse instead.
            if (position > data.size()) {
                return makeError(ErrorCode::InvalidFormat,
                                 "The Radiance HDR pixels are truncated (in scanline " +
                                     std::to_string(row) + " of " + std::to_string(height) + ").");
            }
        }
    }
    return {};
}

}  // namespace

Result<HdrImage> decodeHdr(std::span<const std::uint8_t> encoded) {
    if (encoded.empty() || encoded.size() > static_cast<std::size_t>(INT32_MAX)) {
        return makeError(ErrorCode::InvalidFormat, "HDR data is empty or too large (" +
                                                       std::to_string(encoded.size()) + " bytes).");
    }
    const int length = static_cast<int>(encoded.size());
    // stbi_loadf would also accept a PNG or JPEG and return it linearised; an environment must
    // be real radiance, so anything but Radiance RGBE is refused.
    if (!stbi_is_hdr_from_memory(encoded.data(), length)) {
        return makeError(ErrorCode::InvalidFormat,
                         "The data is not a Radiance HDR image (no '#?RADIANCE' or '#?RGBE' "
                         "signature).");
    }
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(encoded.data(), length, &width, &height, &channels)) {
        return makeError(
            ErrorCode::InvalidFormat,
            std::string("The Radiance HDR header is malformed (") + stbi_failure_reason() + ").");
    }
    // Checked before decoding: a hostile header must not make stb allocate gigabytes.
    if (width <= 0 || height <= 0 || static_cast<std::uint32_t>(width) > kMaxImageDimension ||
        static_cast<std::uint32_t>(height) > kMaxImageDimension) {
        return makeError(ErrorCode::LimitExceeded,
                         "HDR image size " + sizeText(width, height) + " is outside 1.." +
                             std::to_string(kMaxImageDimension) + " on a side.");
    }
    ENCORE_TRY(checkRunLengthScanlines(encoded, static_cast<std::uint32_t>(width),
                                       static_cast<std::uint32_t>(height)));
    std::unique_ptr<float, StbiFreeFloat> pixels(
        stbi_loadf_from_memory(encoded.data(), length, &width, &height, &channels, 3));
    if (!pixels) {
        return makeError(ErrorCode::InvalidFormat, "Decoding the Radiance HDR pixels of a " +
                                                       sizeText(width, height) + " image failed (" +
                                                       stbi_failure_reason() + ").");
    }
    HdrImage image;
    image.width = static_cast<std::uint32_t>(width);
    image.height = static_cast<std::uint32_t>(height);
    const std::size_t count = std::size_t(image.width) * image.height * 3;
    image.rgb.assign(pixels.get(), pixels.get() + count);
    return image;
}

Result<HdrImage> readHdr(const std::filesystem::path& path) {
    ENCORE_TRY_ASSIGN(auto bytes, readFile(path));  // readFile's messages already name the path.
    auto image = decodeHdr(bytes);
    if (!image) {
        return image.error().withContext("'" + path.string() + "'");
    }
    return image;
}

HdrImage makeUniformEnvironment(float r, float g, float b, std::uint32_t width) {
    HdrImage image;
    image.height = std::max(width / 2, 1u);
    image.width = image.height * 2;  // The panorama convention: width = 2 * height.
    image.rgb.resize(std::size_t(image.width) * image.height * 3);
    for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
        image.rgb[i] = r;
        image.rgb[i + 1] = g;
        image.rgb[i + 2] = b;
    }
    return image;
}

}  // namespace encore::image
