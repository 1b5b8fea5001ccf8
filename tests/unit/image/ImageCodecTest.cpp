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

TEST(ImageCodecTest, EmptyImageCannotBeEncoded) {
    EXPECT_FALSE(encodePng(ImageRgba8{}).ok());
}

}  // namespace
}  // namespace encore::image
