#include "batch/RgbaPng.h"

#include <algorithm>
#include <cmath>

#include "image/PngWriter.h"

namespace encore::batch {

std::uint32_t pngSample(float value, std::uint8_t bitDepth) {
    const double top = bitDepth == 16 ? 65535.0 : 255.0;
    return std::uint32_t(std::lround(std::clamp(double(value), 0.0, 1.0) * top));
}

Result<std::vector<std::uint8_t>> encodeRgbaPng(std::span<const float> rgba,
                                                std::uint32_t width,
                                                std::uint32_t height,
                                                std::uint8_t bitDepth,
                                                image::PngCompression compression) {
    const bool sixteen = bitDepth == 16;
    std::vector<std::uint8_t> samples(rgba.size() * (sixteen ? 2 : 1));
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        const std::uint32_t value = pngSample(rgba[i], bitDepth);
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
