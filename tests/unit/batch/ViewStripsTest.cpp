// cropStrip: one view's strip of a wide read-back image, including a strip of width 0 (no
// pixels, so its vector's data() is null: issue 32's copies must accept that).

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "batch/ViewStrips.h"

namespace encore::batch {
namespace {

// Two rows of three RGBA8 pixels; pixel (x, y) holds 10 * y + x in every channel.
image::ImageRgba8 wideImage() {
    image::ImageRgba8 wide;
    wide.width = 3;
    wide.height = 2;
    for (std::uint32_t y = 0; y < wide.height; ++y) {
        for (std::uint32_t x = 0; x < wide.width; ++x) {
            wide.pixels.insert(wide.pixels.end(), 4, std::uint8_t(10 * y + x));
        }
    }
    return wide;
}

TEST(ViewStripsTest, CropsOneStrip) {
    const image::ImageRgba8 strip = cropStrip(wideImage(), 2, 1);
    EXPECT_EQ(strip.width, 1u);
    EXPECT_EQ(strip.height, 2u);
    EXPECT_EQ(strip.pixels, (std::vector<std::uint8_t>{2, 2, 2, 2, 12, 12, 12, 12}));
}

TEST(ViewStripsTest, StripOfWidthZeroHasNoPixels) {
    const image::ImageRgba8 strip = cropStrip(wideImage(), 0, 0);
    EXPECT_EQ(strip.width, 0u);
    EXPECT_EQ(strip.height, 2u);
    EXPECT_TRUE(strip.pixels.empty());
}

}  // namespace
}  // namespace encore::batch
