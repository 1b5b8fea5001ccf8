#include "image/ImageResize.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "image/Srgb.h"

namespace encore::image {

namespace {

// The source pixels one destination pixel covers along an axis, with their coverage weights
// (summing to 1).
struct Footprint {
    std::uint32_t first = 0;
    std::vector<float> weights;
};

std::vector<Footprint> footprints(std::uint32_t sourceLength, std::uint32_t targetLength) {
    const double scale = double(sourceLength) / double(targetLength);
    std::vector<Footprint> result(targetLength);
    for (std::uint32_t i = 0; i < targetLength; ++i) {
        const double begin = i * scale;
        const double end = std::min(double(sourceLength), (i + 1) * scale);
        Footprint& footprint = result[i];
        footprint.first = static_cast<std::uint32_t>(begin);
        for (std::uint32_t s = footprint.first; s < sourceLength && double(s) < end; ++s) {
            const double covered = std::min(end, double(s) + 1.0) - std::max(begin, double(s));
            footprint.weights.push_back(float(covered / (end - begin)));
        }
    }
    return result;
}

const std::array<float, 256>& srgbToLinearTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> values{};
        for (int i = 0; i < 256; ++i) {
            values[i] = float(srgbToLinear(i / 255.0));
        }
        return values;
    }();
    return table;
}

}  // namespace

ImageSize fitWithin(ImageSize size, std::uint32_t maxDimension) {
    maxDimension = std::max(maxDimension, 1u);
    if (size.width <= maxDimension && size.height <= maxDimension) {
        return size;
    }
    const double scale = double(maxDimension) / double(std::max(size.width, size.height));
    auto side = [&](std::uint32_t length) {
        const auto scaled = static_cast<std::uint32_t>(std::lround(length * scale));
        return std::clamp(scaled, 1u, maxDimension);
    };
    return {side(size.width), side(size.height)};
}

ReusedBytes downscaleRgba8(std::span<const std::uint8_t> pixels,
                           ImageSize source,
                           ImageSize target,
                           PixelEncoding encoding) {
    assert(pixels.size() == std::size_t(source.width) * source.height * 4);
    assert(target.width >= 1 && target.height >= 1);
    assert(target.width <= source.width && target.height <= source.height);
    const std::vector<Footprint> columns = footprints(source.width, target.width);
    const std::vector<Footprint> rows = footprints(source.height, target.height);
    const std::array<float, 256>& toLinear = srgbToLinearTable();
    const bool srgb = encoding == PixelEncoding::Srgb;

    ReusedBytes result(std::size_t(target.width) * target.height * 4);  // Every byte written.
    std::vector<float> accumulated(std::size_t(target.width) * 4);
    for (std::uint32_t y = 0; y < target.height; ++y) {
        std::fill(accumulated.begin(), accumulated.end(), 0.0f);
        const Footprint& row = rows[y];
        for (std::size_t r = 0; r < row.weights.size(); ++r) {
            const std::uint8_t* sourceRow =
                pixels.data() + std::size_t(row.first + r) * source.width * 4;
            for (std::uint32_t x = 0; x < target.width; ++x) {
                const Footprint& column = columns[x];
                float* sum = &accumulated[std::size_t(x) * 4];
                for (std::size_t c = 0; c < column.weights.size(); ++c) {
                    const float weight = row.weights[r] * column.weights[c];
                    const std::uint8_t* texel = sourceRow + std::size_t(column.first + c) * 4;
                    for (int channel = 0; channel < 3; ++channel) {
                        sum[channel] +=
                            weight * (srgb ? toLinear[texel[channel]] : texel[channel] / 255.0f);
                    }
                    sum[3] += weight * (texel[3] / 255.0f);
                }
            }
        }
        std::uint8_t* out = result.data() + std::size_t(y) * target.width * 4;
        for (std::size_t i = 0; i < accumulated.size(); ++i) {
            const bool colour = i % 4 != 3;
            out[i] = srgb && colour ? linearToSrgb8(accumulated[i])
                                    : static_cast<std::uint8_t>(std::lround(
                                          std::clamp(accumulated[i], 0.0f, 1.0f) * 255.0f));
        }
    }
    return result;
}

std::vector<float> downscaleRgbFloat(std::span<const float> pixels,
                                     ImageSize source,
                                     ImageSize target) {
    assert(pixels.size() == std::size_t(source.width) * source.height * 3);
    assert(target.width >= 1 && target.height >= 1);
    assert(target.width <= source.width && target.height <= source.height);
    const std::vector<Footprint> columns = footprints(source.width, target.width);
    const std::vector<Footprint> rows = footprints(source.height, target.height);
    std::vector<float> result(std::size_t(target.width) * target.height * 3, 0.0f);
    for (std::uint32_t y = 0; y < target.height; ++y) {
        float* out = result.data() + std::size_t(y) * target.width * 3;
        const Footprint& row = rows[y];
        for (std::size_t r = 0; r < row.weights.size(); ++r) {
            const float* sourceRow = pixels.data() + std::size_t(row.first + r) * source.width * 3;
            for (std::uint32_t x = 0; x < target.width; ++x) {
                const Footprint& column = columns[x];
                for (std::size_t c = 0; c < column.weights.size(); ++c) {
                    const float weight = row.weights[r] * column.weights[c];
                    const float* texel = sourceRow + std::size_t(column.first + c) * 3;
                    for (int channel = 0; channel < 3; ++channel) {
                        out[x * 3 + channel] += weight * texel[channel];
                    }
                }
            }
        }
    }
    return result;
}

}  // namespace encore::image
