#pragma once

// The sRGB transfer function (IEC 61966-2-1).

#include <cmath>

namespace encore::image {

// An sRGB-encoded value in 0..1 to linear.
inline double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace encore::image
