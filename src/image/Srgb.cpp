#include "image/Srgb.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace encore::image {

std::uint8_t encodeSrgb8(float linear) {
    const double encoded = linearToSrgb(std::clamp(double(linear), 0.0, 1.0));
    return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

namespace {

// thresholds[k]: the least float that encodeSrgb8 takes to more than k. The encoding only grows
// with its argument, and non-negative floats order as their bits do, so a bisection over the
// bits finds each exactly.
const std::array<float, 255>& srgb8Thresholds() {
    static const std::array<float, 255> thresholds = [] {
        std::array<float, 255> values{};
        for (int k = 0; k < 255; ++k) {
            std::uint32_t low = 0;                                    // encodes to <= k
            std::uint32_t high = std::bit_cast<std::uint32_t>(1.0f);  // encodes to 255 > k
            while (high - low > 1) {
                const std::uint32_t middle = low + (high - low) / 2;
                if (encodeSrgb8(std::bit_cast<float>(middle)) > k) {
                    high = middle;
                } else {
                    low = middle;
                }
            }
            values[k] = std::bit_cast<float>(high);
        }
        return values;
    }();
    return thresholds;
}

}  // namespace

std::uint8_t linearToSrgb8(float linear) {
    // Counts the thresholds at or below `linear`: a branchless binary search (selects, not
    // jumps, so that texels of every shade cost alike).
    static const std::array<float, 255>& thresholds = srgb8Thresholds();
    std::uint32_t below = 0;  // thresholds[0 .. below) are <= linear.
    for (std::uint32_t step = 128; step > 0; step /= 2) {
        const std::uint32_t next = below + step;
        below = next <= 255 && thresholds[next - 1] <= linear ? next : below;
    }
    return static_cast<std::uint8_t>(below);
}

}  // namespace encore::image
