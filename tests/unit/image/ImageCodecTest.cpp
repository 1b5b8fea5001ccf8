#include <gtest/gtest.h>

#include "TestPaths.h"
#include "encore/image/ImageCodec.h"

namespace encore::image {
namespace {

TEST(ImageCodecTest, PngRoundTripIsExact) {
    ImageRgba8 image{3, 2, {}};
    for (std::uint32_t i = 0; i < 3 * 2 * 4; ++i) {
        image.pixels.push_back(static_cast<std::uint8_t>(i * 10));
    }
    auto dir = test::makeTempDir("image");
    ASSERT_TRUE(writePng(dir / "a.png", image).ok());
    auto read = readImage(dir / "a.png");
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->width, 3u);
    EXPECT_EQ(read->height, 2u);
    EXPECT_EQ(read->pixels, image.pixels);
}

TEST(ImageCodecTest, GarbageIsAnError) {
    const std::vector<std::uint8_t> garbage = {1, 2, 3, 4, 5, 6, 7, 8};
    auto decoded = decodeImage(garbage);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
}

// A PNG header promising 16384 x 16384 pixels (within the side limit) is refused before any
// allocation: decoding it would need about 2 GiB (found by the loader fuzzer).
TEST(ImageCodecTest, HugeAreaIsRefusedBeforeDecoding) {
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,  // Signature.
                                     0, 0, 0, 13, 'I', 'H', 'D', 'R',               // IHDR.
                                     0, 0, 0x40, 0, 0, 0, 0x40, 0,                  // 16384^2.
                                     8, 6, 0, 0, 0,                                 // RGBA8.
                                     0, 0, 0, 0};                                   // CRC.
    auto decoded = decodeImage(png);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(decoded.error().message.find("16384x16384"), std::string::npos)
        << decoded.error().message;
}

TEST(ImageCodecTest, EmptyImageCannotBeEncoded) {
    EXPECT_FALSE(encodePng(ImageRgba8{}).ok());
}

}  // namespace
}  // namespace encore::image
