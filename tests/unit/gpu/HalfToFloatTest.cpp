#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "gpu/Readback.h"

namespace encore::gpu {
namespace {

// Every one of the 65,536 half floats reads as IEEE 754 defines it: sign, 5-bit exponent biased
// by 15, 10-bit mantissa, subnormals below exponent 1, infinities and NaNs at exponent 31.
TEST(HalfToFloatTest, EveryHalfHasItsIeeeValue) {
    for (std::uint32_t half = 0; half <= 0xffffu; ++half) {
        SCOPED_TRACE(half);
        const double sign = (half & 0x8000u) ? -1.0 : 1.0;
        const int exponent = int(half >> 10) & 0x1f;
        const int mantissa = int(half & 0x3ffu);
        const float value = halfToFloat(std::uint16_t(half));
        if (exponent == 31) {
            if (mantissa == 0) {
                EXPECT_EQ(value, float(sign * INFINITY));
            } else {
                EXPECT_TRUE(std::isnan(value));
            }
            continue;
        }
        const double expected = exponent == 0
                                    ? sign * std::ldexp(double(mantissa), -24)
                                    : sign * std::ldexp(double(mantissa | 0x400), exponent - 25);
        EXPECT_EQ(value, float(expected));
        EXPECT_EQ(std::signbit(value), (half & 0x8000u) != 0);  // -0 stays negative.
    }
}

}  // namespace
}  // namespace encore::gpu
