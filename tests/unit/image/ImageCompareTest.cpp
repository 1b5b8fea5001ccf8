#include "image/ImageCompare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

namespace encore::image {
namespace {

ImageRgba8 filled(std::uint32_t width, std::uint32_t height, std::array<std::uint8_t, 4> rgba) {
    ImageRgba8 image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * height * 4);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = rgba[i % 4];
    }
    return image;
}

// The deterministic images of the reference values below; an independent SSIM implementation
// (direct 2D filtering in double precision, written separately from ImageCompare.cpp) built the
// same images with the same formulas and this LCG.
class Lcg {
  public:
    explicit Lcg(std::uint32_t seed) : mState(seed) {}
    std::uint32_t nextByte() {
        mState = mState * 1664525u + 1013904223u;
        return mState >> 24;
    }

  private:
    std::uint32_t mState;
};

ImageRgba8 gradient(std::uint32_t width, std::uint32_t height) {
    ImageRgba8 image = filled(width, height, {0, 0, 0, 255});
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t((x * 5 + y * 2) % 256);
            p[1] = std::uint8_t((x * y) % 256);
            p[2] = std::uint8_t((255 + 256 * 4 - x * 3) % 256);  // (255 - 3x) mod 256.
        }
    }
    return image;
}

// Adds seeded noise in -20..20 to every colour channel, clamped.
ImageRgba8 noisy(const ImageRgba8& image, std::uint32_t seed) {
    ImageRgba8 out = image;
    Lcg lcg(seed);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                const int value = int(image.pixel(x, y)[c]) + int(lcg.nextByte() % 41) - 20;
                out.pixel(x, y)[c] = std::uint8_t(std::clamp(value, 0, 255));
            }
        }
    }
    return out;
}

ImageRgba8 randomImage(std::uint32_t width, std::uint32_t height, std::uint32_t seed) {
    ImageRgba8 image = filled(width, height, {0, 0, 0, 0});
    Lcg lcg(seed);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const std::uint8_t byte = std::uint8_t(lcg.nextByte());
        image.pixels[i] = i % 4 == 3 ? 255 : byte;
    }
    return image;
}

// Moves the image one pixel to the right, repeating the first column.
ImageRgba8 shiftedRight(const ImageRgba8& image) {
    ImageRgba8 out = image;
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 1; x < image.width; ++x) {
            std::copy_n(image.pixel(x - 1, y), 4, out.pixel(x, y));
        }
    }
    return out;
}

TEST(ImageCompareTest, IdenticalImagesHaveSsimOneAndNoError) {
    const ImageRgba8 image = gradient(48, 40);
    auto ssim = ssimLuminance(image, image);
    ASSERT_TRUE(ssim.ok()) << ssim.error().message;
    EXPECT_NEAR(*ssim, 1.0, 1e-12);
    auto error = colorError(image, image);
    ASSERT_TRUE(error.ok());
    EXPECT_EQ(error->meanAbsolute, 0.0);
    EXPECT_EQ(error->maxAbsolute, 0);
    EXPECT_EQ(error->fractionOverThreshold, 0.0);
}

TEST(ImageCompareTest, AlphaIsIgnored) {
    ImageRgba8 opaque = gradient(16, 16);
    ImageRgba8 clear = opaque;
    for (std::size_t i = 3; i < clear.pixels.size(); i += 4) {
        clear.pixels[i] = 0;
    }
    EXPECT_NEAR(*ssimLuminance(opaque, clear), 1.0, 1e-12);
    EXPECT_EQ(colorError(opaque, clear)->maxAbsolute, 0);
}

// Flat images have no variance, so SSIM reduces to its luminance term everywhere:
// (2 a b + C1) / (a^2 + b^2 + C1).
TEST(ImageCompareTest, FlatImagesFollowTheLuminanceTerm) {
    const double c1 = (0.01 * 255) * (0.01 * 255);
    const double a = 100.0;
    const double b = 150.0;
    auto ssim =
        ssimLuminance(filled(20, 15, {100, 100, 100, 255}), filled(20, 15, {150, 150, 150, 255}));
    ASSERT_TRUE(ssim.ok());
    EXPECT_NEAR(*ssim, (2 * a * b + c1) / (a * a + b * b + c1), 1e-9);

    // Luma weights: pure green at 200 against black is luma 0.7152 * 200 against 0.
    const double y = 0.7152 * 200.0;
    auto green = ssimLuminance(filled(11, 11, {0, 200, 0, 255}), filled(11, 11, {0, 0, 0, 255}));
    EXPECT_NEAR(*green, c1 / (y * y + c1), 1e-9);

    auto error = colorError(filled(4, 4, {10, 20, 30, 255}), filled(4, 4, {13, 20, 0, 7}));
    ASSERT_TRUE(error.ok());
    EXPECT_DOUBLE_EQ(error->meanAbsolute, 11.0);  // (3 + 0 + 30) / 3.
    EXPECT_EQ(error->maxAbsolute, 30);
    EXPECT_EQ(error->fractionOverThreshold, 1.0);
}

TEST(ImageCompareTest, MatchesAnIndependentImplementation) {
    struct Case {
        const char* name;
        ImageRgba8 a, b;
        double ssim;
        double firstLocal;  // The map's value at (0, 0).
        std::uint32_t mapWidth, mapHeight;
        double meanAbsolute;
        int maxAbsolute;
        double fractionOver;
    };
    const ImageRgba8 base = gradient(48, 40);
    const Case cases[] = {
        {"noisy", base, noisy(base, 7), 0.9670536801, 0.6989102238, 38, 30, 10.1939236111, 20,
         0.4739583333},
        {"random", base, randomImage(48, 40, 12345), 0.0017141575, 0.0110293039, 38, 30,
         84.7677083333, 255, 0.9973958333},
        {"shifted", base, shiftedRight(base), 0.6148290518, 0.9885769016, 38, 30, 14.5531250000,
         251, 0.5744791667},
        // Smaller than the window: the largest odd window that fits (5x5).
        {"small", gradient(9, 6), noisy(gradient(9, 6), 3), 0.6229814117, 0.5937508297, 5, 2,
         9.0061728395, 20, 0.3703703704},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        auto map = ssimLuminanceMap(c.a, c.b);
        ASSERT_TRUE(map.ok()) << map.error().message;
        EXPECT_NEAR(map->mean, c.ssim, 1e-4);
        EXPECT_NEAR(*ssimLuminance(c.a, c.b), map->mean, 1e-15);
        EXPECT_EQ(map->width, c.mapWidth);
        EXPECT_EQ(map->height, c.mapHeight);
        ASSERT_EQ(map->values.size(), std::size_t(c.mapWidth) * c.mapHeight);
        EXPECT_NEAR(map->values[0], c.firstLocal, 1e-4);
        auto error = colorError(c.a, c.b);
        ASSERT_TRUE(error.ok());
        EXPECT_NEAR(error->meanAbsolute, c.meanAbsolute, 1e-9);
        EXPECT_EQ(error->maxAbsolute, c.maxAbsolute);
        EXPECT_NEAR(error->fractionOverThreshold, c.fractionOver, 1e-9);
    }
}

TEST(ImageCompareTest, SsimIsSymmetric) {
    const ImageRgba8 a = gradient(30, 20);
    const ImageRgba8 b = noisy(a, 99);
    EXPECT_NEAR(*ssimLuminance(a, b), *ssimLuminance(b, a), 1e-12);
}

TEST(ImageCompareTest, RefusesDifferentSizesAndEmptyImages) {
    auto different = ssimLuminance(filled(4, 4, {0, 0, 0, 255}), filled(4, 5, {0, 0, 0, 255}));
    ASSERT_FALSE(different.ok());
    EXPECT_EQ(different.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(different.error().message.find("(4x4 and 4x5)"), std::string::npos)
        << different.error().message;
    EXPECT_FALSE(colorError(filled(4, 4, {0, 0, 0, 255}), filled(5, 4, {0, 0, 0, 255})).ok());
    EXPECT_FALSE(ssimLuminance(ImageRgba8{}, ImageRgba8{}).ok());
    EXPECT_FALSE(colorError(ImageRgba8{}, ImageRgba8{}).ok());
    ImageRgba8 truncated = filled(4, 4, {0, 0, 0, 255});
    truncated.pixels.resize(10);
    EXPECT_FALSE(ssimLuminance(truncated, truncated).ok());
}

TEST(ImageCompareTest, DifferenceImageScalesAndClamps) {
    const ImageRgba8 a = filled(3, 2, {10, 200, 50, 0});
    const ImageRgba8 b = filled(3, 2, {20, 100, 50, 9});
    const ImageRgba8 difference = differenceImage(a, b, 4.0f);
    ASSERT_EQ(difference.width, 3u);
    ASSERT_EQ(difference.height, 2u);
    const std::uint8_t* p = difference.pixel(2, 1);
    EXPECT_EQ(p[0], 40);   // |10 - 20| * 4.
    EXPECT_EQ(p[1], 255);  // 100 * 4, clamped.
    EXPECT_EQ(p[2], 0);
    EXPECT_EQ(p[3], 255);  // Opaque whatever the inputs' alpha.
    EXPECT_EQ(differenceImage(a, b, 0.5f).pixel(0, 0)[0], 5);
    EXPECT_EQ(differenceImage(a, b, -1.0f).pixel(0, 0)[0], 0);
    // Different sizes: the common area.
    const ImageRgba8 small = differenceImage(a, filled(2, 5, {0, 0, 0, 255}), 1.0f);
    EXPECT_EQ(small.width, 2u);
    EXPECT_EQ(small.height, 2u);
    EXPECT_EQ(differenceImage(a, ImageRgba8{}, 1.0f).pixels.size(), 0u);
}

TEST(ImageCompareTest, SideBySideIsTopAlignedWithGreyGaps) {
    const ImageRgba8 images[] = {filled(3, 2, {255, 0, 0, 0}), filled(2, 4, {0, 255, 0, 255}),
                                 filled(1, 1, {0, 0, 255, 128})};
    const ImageRgba8 row = sideBySide(images, 4);
    ASSERT_EQ(row.width, 3u + 4 + 2 + 4 + 1);
    ASSERT_EQ(row.height, 4u);
    ASSERT_EQ(row.pixels.size(), std::size_t(row.width) * row.height * 4);
    auto rgba = [&](std::uint32_t x, std::uint32_t y) {
        const std::uint8_t* p = row.pixel(x, y);
        return std::array<std::uint8_t, 4>{p[0], p[1], p[2], p[3]};
    };
    using Rgba = std::array<std::uint8_t, 4>;
    const Rgba grey{kSideBySideGrey, kSideBySideGrey, kSideBySideGrey, 255};
    EXPECT_EQ(rgba(0, 0), (Rgba{255, 0, 0, 255}));  // Made opaque.
    EXPECT_EQ(rgba(2, 1), (Rgba{255, 0, 0, 255}));
    EXPECT_EQ(rgba(0, 2), grey);  // Below the shorter first image.
    EXPECT_EQ(rgba(3, 0), grey);  // The gap.
    EXPECT_EQ(rgba(6, 3), grey);
    EXPECT_EQ(rgba(7, 0), (Rgba{0, 255, 0, 255}));
    EXPECT_EQ(rgba(8, 3), (Rgba{0, 255, 0, 255}));
    EXPECT_EQ(rgba(13, 0), (Rgba{0, 0, 255, 255}));
    EXPECT_EQ(rgba(13, 1), grey);

    EXPECT_EQ(sideBySide(std::span(images, 1), 4).width, 3u);  // No gap after the last image.
    EXPECT_EQ(sideBySide({}, 4).pixels.size(), 0u);
}

}  // namespace
}  // namespace encore::image
