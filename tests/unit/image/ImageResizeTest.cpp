// Downscaling images that exceed a device's texture size: the size keeps the aspect ratio, and
// the box filter keeps the mean for any ratio, averaging sRGB colour in linear light.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "image/ImageResize.h"
#include "image/Srgb.h"

namespace encore::image {
namespace {

std::vector<std::uint8_t> solid(ImageSize size,
                                std::uint8_t r,
                                std::uint8_t g,
                                std::uint8_t b,
                                std::uint8_t a) {
    std::vector<std::uint8_t> pixels;
    for (std::uint32_t i = 0; i < size.width * size.height; ++i) {
        pixels.insert(pixels.end(), {r, g, b, a});
    }
    return pixels;
}

TEST(ImageResizeTest, FitWithinKeepsTheAspectRatioAndLeavesFittingImagesAlone) {
    EXPECT_EQ(fitWithin({600, 300}, 256), (ImageSize{256, 128}));
    EXPECT_EQ(fitWithin({300, 600}, 256), (ImageSize{128, 256}));
    EXPECT_EQ(fitWithin({9000, 6}, 8192), (ImageSize{8192, 5}));    // 5.46 rounds to 5.
    EXPECT_EQ(fitWithin({100000, 1}, 8192), (ImageSize{8192, 1}));  // Never below one pixel.
    EXPECT_EQ(fitWithin({256, 256}, 256), (ImageSize{256, 256}));
    EXPECT_EQ(fitWithin({17, 3}, 256), (ImageSize{17, 3}));
}

TEST(ImageResizeTest, SolidImagesStaySolidAtAnyRatio) {
    const ImageSize source{37, 23};
    const auto pixels = solid(source, 200, 100, 50, 128);
    for (ImageSize target : {ImageSize{16, 10}, ImageSize{7, 5}, ImageSize{1, 1}, source}) {
        for (PixelEncoding encoding : {PixelEncoding::Srgb, PixelEncoding::Linear}) {
            const auto result = downscaleRgba8(pixels, source, target, encoding);
            ASSERT_EQ(result.size(), std::size_t(target.width) * target.height * 4);
            for (std::size_t i = 0; i < result.size(); i += 4) {
                EXPECT_NEAR(result[i], 200, 1);
                EXPECT_NEAR(result[i + 1], 100, 1);
                EXPECT_NEAR(result[i + 2], 50, 1);
                EXPECT_EQ(result[i + 3], 128);
            }
        }
    }
}

TEST(ImageResizeTest, AveragesLinearDataArithmeticallyAndSrgbColourInLinearLight) {
    // A 2x1 black-and-white pair becomes one pixel.
    std::vector<std::uint8_t> pair = {0, 0, 0, 0, 255, 255, 255, 255};
    const auto linear = downscaleRgba8(pair, {2, 1}, {1, 1}, PixelEncoding::Linear);
    EXPECT_EQ(linear[0], 128);  // 127.5 rounds up.
    EXPECT_EQ(linear[3], 128);
    const auto srgb = downscaleRgba8(pair, {2, 1}, {1, 1}, PixelEncoding::Srgb);
    EXPECT_EQ(srgb[0], 188);  // sRGB encoding of linear 0.5.
    EXPECT_EQ(srgb[3], 128);  // Alpha is linear.
}

TEST(ImageResizeTest, FractionalFootprintsWeighPixelsByCoverage) {
    // Three columns 0, 90, 180 into two: [0, 1.5) and [1.5, 3).
    std::vector<std::uint8_t> row = {0, 0, 0, 255, 90, 90, 90, 255, 180, 180, 180, 255};
    const auto result = downscaleRgba8(row, {3, 1}, {2, 1}, PixelEncoding::Linear);
    EXPECT_EQ(result[0], 30);   // (0 * 1 + 90 * 0.5) / 1.5
    EXPECT_EQ(result[4], 150);  // (90 * 0.5 + 180 * 1) / 1.5
    EXPECT_EQ(result[3], 255);
    // Rows work the same way: a vertical gradient keeps its mean.
    const ImageSize tall{1, 90};
    std::vector<std::uint8_t> gradient;
    double sum = 0;
    for (std::uint32_t y = 0; y < tall.height; ++y) {
        const auto value = static_cast<std::uint8_t>(y * 2);
        gradient.insert(gradient.end(), {value, value, value, 255});
        sum += value;
    }
    const auto squeezed = downscaleRgba8(gradient, tall, {1, 7}, PixelEncoding::Linear);
    double squeezedSum = 0;
    for (std::size_t i = 0; i < squeezed.size(); i += 4) {
        squeezedSum += squeezed[i];
    }
    EXPECT_NEAR(squeezedSum / 7.0, sum / 90.0, 0.5);
}

TEST(ImageResizeTest, HdrPanoramasKeepTheirMeanRadiance) {
    // Radiance beyond 1 is kept, not clamped: a bright column spreads into its neighbours.
    const ImageSize source{5, 2};
    std::vector<float> pixels(source.width * source.height * 3, 0.25f);
    pixels[2 * 3] = 100.0f;  // Red of column 2, row 0.
    const auto result = downscaleRgbFloat(pixels, source, {2, 1});
    ASSERT_EQ(result.size(), 6u);
    // Column footprints [0, 2.5) and [2.5, 5) over both rows: column 2 of row 0 weighs
    // 0.5 (its half) * 0.5 (one of two rows) / 2.5 columns = 0.1 in each.
    EXPECT_NEAR(result[0], 0.25f * 0.9f + 100.0f * 0.1f, 1e-4f);
    EXPECT_NEAR(result[3], 0.25f * 0.9f + 100.0f * 0.1f, 1e-4f);
    EXPECT_NEAR(result[1], 0.25f, 1e-6f);
}

// The search that downscaling encodes sRGB with gives what the formula gives: at a million
// values across 0..1 and beyond, and around every step of the result (the threshold float and
// its neighbours).
TEST(ImageResizeTest, Srgb8EncodingWithoutPowMatchesTheFormula) {
    for (int i = -100000; i <= 1100000; ++i) {
        const float linear = float(i) / 1000000.0f;
        ASSERT_EQ(linearToSrgb8(linear), encodeSrgb8(linear)) << linear;
    }
    for (int k = 0; k < 255; ++k) {
        // Where the formula steps from k to k + 1: bisect as the implementation does not.
        float low = 0.0f;
        float high = 1.0f;
        for (int step = 0; step < 60; ++step) {
            const float middle = (low + high) / 2;
            (encodeSrgb8(middle) > k ? high : low) = middle;
        }
        for (float value : {std::nextafter(high, 0.0f), high, std::nextafter(high, 2.0f), low}) {
            ASSERT_EQ(linearToSrgb8(value), encodeSrgb8(value)) << value << " near step " << k;
        }
    }
    EXPECT_EQ(linearToSrgb8(-1.0f), 0);
    EXPECT_EQ(linearToSrgb8(0.0f), 0);
    EXPECT_EQ(linearToSrgb8(1.0f), 255);
    EXPECT_EQ(linearToSrgb8(7.0f), 255);
}

}  // namespace
}  // namespace encore::image
