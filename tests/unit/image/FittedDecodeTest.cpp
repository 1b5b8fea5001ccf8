// decodeImageWithin (FittedDecode.h): images decoded to fit within a maximum size.

#include <gtest/gtest.h>

#include <cstdio>  // Before jpeglib.h, which uses FILE and size_t without including them.

#include <jpeglib.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "TextureFixtures.h"
#include "encore/image/ImageCodec.h"
#include "image/FittedDecode.h"

namespace encore::image {
namespace {

using Bytes = std::vector<std::uint8_t>;

// A baseline JPEG whose blue channel is 40 on the left half and 220 on the right, over
// gradients.
Bytes encodeJpeg(std::uint32_t width, std::uint32_t height) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &buffer, &size);
    info.image_width = width;
    info.image_height = height;
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 90, TRUE);
    jpeg_start_compress(&info, TRUE);
    Bytes row(std::size_t(width) * 3);
    while (info.next_scanline < height) {
        for (std::uint32_t x = 0; x < width; ++x) {
            row[x * 3] = std::uint8_t(x * 255 / width);
            row[x * 3 + 1] = std::uint8_t(info.next_scanline * 255 / height);
            row[x * 3 + 2] = std::uint8_t(x < width / 2 ? 40 : 220);
        }
        JSAMPROW rows[1] = {row.data()};
        jpeg_write_scanlines(&info, rows, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    Bytes jpeg(buffer, buffer + size);
    std::free(buffer);
    return jpeg;
}

// A baseline JPEG decodes at a fraction of its size when a limit asks for less (libjpeg's DCT
// scaling), even one wider than Encore decodes whole; every format is then box-filtered to the
// limit, keeping the aspect ratio, and reports the file's size.
TEST(FittedDecodeTest, ImagesDecodeWithinAMaximumSize) {
    const Bytes wide = encodeJpeg(20000, 200);
    EXPECT_FALSE(decodeImage(wide).ok()) << "wider than kMaxImageDimension";
    auto fitted = decodeImageWithin(wide, 4096, PixelEncoding::Srgb);
    ASSERT_TRUE(fitted.ok()) << fitted.error().message;
    EXPECT_EQ(fitted->source, (ImageSize{20000, 200}));
    EXPECT_EQ(fitted->image.width, 4096u);
    EXPECT_EQ(fitted->image.height, 41u);
    ASSERT_EQ(fitted->image.pixels.size(), 4096u * 41 * 4);
    // The left half's blue channel is 40, the right half's 220 (the gradients change slowly).
    EXPECT_NEAR(fitted->image.pixels[(20 * 4096 + 100) * 4 + 2], 40, 6);
    EXPECT_NEAR(fitted->image.pixels[(20 * 4096 + 4000) * 4 + 2], 220, 6);

    const Bytes png = test::encodePngBytes(test::solidImage({10, 200, 30, 255}, 300, 600));
    auto small = decodeImageWithin(png, 100, PixelEncoding::Linear);
    ASSERT_TRUE(small.ok()) << small.error().message;
    EXPECT_EQ(small->source, (ImageSize{300, 600}));
    EXPECT_EQ(small->image.width, 50u);
    EXPECT_EQ(small->image.height, 100u);
    EXPECT_EQ(small->image.pixels[0], 10);
    EXPECT_EQ(small->image.pixels[1], 200);
    // Wider than Encore decodes whole: decoded row by row, each row box-filtered as it comes.
    ImageRgba8 halves = test::solidImage({0, 0, 0, 255}, 20000, 100);
    for (std::size_t pixel = 0; pixel < std::size_t(20000) * 100; ++pixel) {
        if (pixel % 20000 >= 10000) {
            std::fill_n(&halves.pixels[pixel * 4], 3, std::uint8_t(255));
        }
    }
    const Bytes huge = test::encodePngBytes(halves);
    EXPECT_FALSE(decodeImage(huge).ok()) << "wider than kMaxImageDimension";
    auto rows = decodeImageWithin(huge, 1000, PixelEncoding::Linear);
    ASSERT_TRUE(rows.ok()) << rows.error().message;
    EXPECT_EQ(rows->source, (ImageSize{20000, 100}));
    EXPECT_EQ(rows->image.width, 1000u);
    EXPECT_EQ(rows->image.height, 5u);
    for (std::uint32_t y = 0; y < 5; ++y) {
        EXPECT_EQ(rows->image.pixels[(y * 1000 + 10) * 4], 0);
        EXPECT_EQ(rows->image.pixels[(y * 1000 + 990) * 4 + 1], 255);
        EXPECT_EQ(rows->image.pixels[(y * 1000 + 990) * 4 + 3], 255);
    }
    // Top half black, bottom half white: the middle row of five is their mean.
    ImageRgba8 stacked = test::solidImage({0, 0, 0, 255}, 20000, 100);
    std::fill(stacked.pixels.begin() + std::ptrdiff_t(20000) * 50 * 4, stacked.pixels.end(),
              std::uint8_t(255));
    auto rowsDown = decodeImageWithin(test::encodePngBytes(stacked), 1000, PixelEncoding::Linear);
    ASSERT_TRUE(rowsDown.ok()) << rowsDown.error().message;
    const int expectedRows[5] = {0, 0, 128, 255, 255};
    for (std::uint32_t y = 0; y < 5; ++y) {
        EXPECT_NEAR(rowsDown->image.pixels[(y * 1000 + 500) * 4], expectedRows[y], 1) << y;
    }
    // sRGB colour is averaged in linear light: the column across the edge is half of each.
    auto srgb = decodeImageWithin(huge, 2000, PixelEncoding::Srgb);
    ASSERT_TRUE(srgb.ok());
    EXPECT_EQ(srgb->image.pixels[999 * 4], 0);
    EXPECT_EQ(srgb->image.pixels[1000 * 4], 255);

    auto kept = decodeImageWithin(png, 0, PixelEncoding::Linear);
    ASSERT_TRUE(kept.ok());
    EXPECT_EQ(kept->image.width, 300u);
    EXPECT_EQ(kept->source, (ImageSize{300, 600}));
}

}  // namespace
}  // namespace encore::image
