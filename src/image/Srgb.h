#pragma once

// The sRGB transfer function (IEC 61966-2-1).

#include <cmath>
#include <cstdint>

namespace encore::image {

// An sRGB-encoded value in 0..1 to linear.
inline double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// A linear value in 0..1 to sRGB-encoded.
inline double linearToSrgb(double linear) {
    return linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// A linear value (clamped to 0..1) sRGB-encoded and rounded to 8 bits, by the formula (pow).
std::uint8_t encodeSrgb8(float linear);
// The same value without pow (a search over the 255 places where the result steps up, found
// once): for images of millions of texels.
std::uint8_t linearToSrgb8(float linear);

}  // namespace encore::image
