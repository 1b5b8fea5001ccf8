#include "batch/RgbaPng.h"

#include <algorithm>
#include <cmath>

#include "image/PngWriter.h"

namespace encore::batch {

Result<std::vector<std::uint8_t>> encodeRgbaPng(std::span<const float> rgba,
                                                std::uint32_t width,
                                                std::uint32_t height,
                                                std::uint8_t bitDepth,
                                                image::PngCompression compression) {
    const bool sixteen = bitDepth == 16;
    const double top = sixteen ? 65535.0 : 255.0;
    std::vector<std::uint8_t> samples(rgba.size() * (sixteen ? 2 : 1));
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        const auto value = std::uint32_t(std::lround(std::clamp(double(rgba[i]), 0.0, 1.0) * top));
        if (sixteen) {
            samples[i * 2] = std::uint8_t(value >> 8);  // PNG is big-endian.
            samples[i * 2 + 1] = std::uint8_t(value & 0xff);
        } else {
            samples[i] = std::uint8_t(value);
        }
    }
    return image::pngOfSamples(width, height, bitDepth, image::PngColor::Rgba, samples,
                               compression);
}

}  // namespace encore::batch
