#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <string_view>

#include "TestPaths.h"
#include "encore/image/ImageCodec.h"
#include "image/RunLengthDeflate.h"

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

// What decodeImage does not check (it ignores checksums, as stb_image did): every chunk's CRC,
// and that zlib inflates the IDAT data, Adler-32 included, to `rawBytes` (filter bytes and rows).
void expectStrictlyValidPng(const std::vector<std::uint8_t>& png, std::size_t rawBytes) {
    const auto be32 = [&](std::size_t at) {
        return std::uint32_t(png[at]) << 24 | std::uint32_t(png[at + 1]) << 16 |
               std::uint32_t(png[at + 2]) << 8 | std::uint32_t(png[at + 3]);
    };
    std::vector<std::uint8_t> idat;
    std::size_t offset = 8;
    while (offset + 12 <= png.size()) {
        const std::uint32_t length = be32(offset);
        ASSERT_LE(offset + 12 + length, png.size());
        const std::string_view type(reinterpret_cast<const char*>(&png[offset + 4]), 4);
        EXPECT_EQ(be32(offset + 8 + length), crc32(0, &png[offset + 4], length + 4)) << type;
        if (type == "IDAT") {
            idat.insert(idat.end(), &png[offset + 8], &png[offset + 8 + length]);
        }
        offset += 12 + length;
    }
    EXPECT_EQ(offset, png.size());
    std::vector<std::uint8_t> raw(rawBytes + 1);
    uLongf rawSize = uLongf(raw.size());
    EXPECT_EQ(uncompress(raw.data(), &rawSize, idat.data(), uLong(idat.size())), Z_OK);
    EXPECT_EQ(rawSize, rawBytes);
}

// A view as `encore batch` writes them: an object on a transparent background, with smooth
// shading and noise. Its PNG decodes to the same pixels, and the 16-bit greyscale form too.
TEST(ImageCodecTest, RenderedViewRoundTripsExactly) {
    ImageRgba8 image{300, 200, ReusedBytes(300 * 200 * 4, 0)};
    std::uint32_t noise = 12345;
    for (std::uint32_t y = 40; y < 170; ++y) {
        for (std::uint32_t x = 60; x < 250; ++x) {
            noise = noise * 1664525u + 1013904223u;
            std::uint8_t* pixel = image.pixel(x, y);
            pixel[0] = std::uint8_t(x + (noise >> 29));
            pixel[1] = std::uint8_t(y * 2);
            pixel[2] = std::uint8_t((x * y) >> 6);
            pixel[3] = x < 64 ? 128 : 255;
        }
    }
    auto encoded = encodePng(image);
    ASSERT_TRUE(encoded.ok()) << encoded.error().message;
    EXPECT_LT(encoded->size(), image.pixels.size() / 2);
    expectStrictlyValidPng(*encoded, (300 * 4 + 1) * 200);
    auto decoded = decodeImage(*encoded);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->width, 300u);
    EXPECT_EQ(decoded->height, 200u);
    EXPECT_TRUE(decoded->pixels == image.pixels);

    ImageGray16 depth{300, 200, {}};
    for (std::uint32_t i = 0; i < 300 * 200; ++i) {
        depth.pixels.push_back(image.pixels[i * 4 + 3] ? std::uint16_t(i * 7) : 0);
    }
    auto depthPng = encodePng16(depth);
    ASSERT_TRUE(depthPng.ok()) << depthPng.error().message;
    expectStrictlyValidPng(*depthPng, (300 * 2 + 1) * 200);
    auto depthDecoded = decodeImage(*depthPng);
    ASSERT_TRUE(depthDecoded.ok()) << depthDecoded.error().message;
    for (std::uint32_t i = 0; i < 300 * 200; ++i) {
        ASSERT_EQ(depthDecoded->pixels[i * 4], depth.pixels[i] >> 8) << i;  // The high byte.
    }
}

// A decoded image's memory serves the next image of its size once freed: a batch decodes the
// same sizes model after model without asking the kernel for fresh pages.
TEST(ImageCodecTest, DecodingAgainReusesTheFreedImagesMemory) {
    ImageRgba8 image{512, 512, ReusedBytes(512 * 512 * 4, 0)};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = static_cast<std::uint8_t>(i * 7 % 251);
    }
    const auto encoded = encodePng(image);
    ASSERT_TRUE(encoded.ok());
    const std::uint8_t* first = nullptr;
    {
        auto decoded = decodeImage(*encoded);
        ASSERT_TRUE(decoded.ok());
        first = decoded->pixels.data();
    }
    const ReusedBlockCounts before = reusedBlockCounts();
    auto again = decodeImage(*encoded);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->pixels.data(), first);
    EXPECT_EQ(reusedBlockCounts().created, before.created);
    EXPECT_EQ(again->pixels, image.pixels);
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
    std::vector<std::uint8_t> png = {0x89, 'P', 'N',  'G', 0x0D, 0x0A, 0x1A, 0x0A,  // Signature.
                                     0,    0,   0,    13,  'I',  'H',  'D',  'R',   // IHDR.
                                     0,    0,   0x40, 0,   0,    0,    0x40, 0,     // 16384^2.
                                     8,    6,   0,    0,   0,                       // RGBA8.
                                     0,    0,   0,    0};                           // CRC.
    auto decoded = decodeImage(png);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(decoded.error().message.find("16384x16384"), std::string::npos)
        << decoded.error().message;
}

// 16-bit samples double what decoding holds: 8192 x 8192 RGBA16 passes the area limit but
// needs 512 MiB of samples, over kMaxDecodedImageBytes.
TEST(ImageCodecTest, SixteenBitImagesAreLimitedByDecodedBytes) {
    std::vector<std::uint8_t> png = {0x89, 'P', 'N',  'G', 0x0D, 0x0A, 0x1A, 0x0A,  // Signature.
                                     0,    0,   0,    13,  'I',  'H',  'D',  'R',   // IHDR.
                                     0,    0,   0x20, 0,   0,    0,    0x20, 0,     // 8192^2.
                                     16,   6,   0,    0,   0,                       // RGBA16.
                                     0,    0,   0,    0};                           // CRC.
    auto decoded = decodeImage(png);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(decoded.error().message.find("512 MiB"), std::string::npos)
        << decoded.error().message;
}

// A chunk declaring more bytes than the file holds is refused before stb_image sizes a buffer
// from it (the loader fuzzer found an IDAT declaring 1.4 GB in a 42 kB file: a 2 GiB realloc).
TEST(ImageCodecTest, ChunkLongerThanTheFileIsRefused) {
    ImageRgba8 image{4, 4, ReusedBytes(4 * 4 * 4, 200)};
    auto encoded = encodePng(image);
    ASSERT_TRUE(encoded.ok());
    std::vector<std::uint8_t> png = *encoded;
    ASSERT_TRUE(decodeImage(png).ok());
    const std::string_view bytes(reinterpret_cast<const char*>(png.data()), png.size());
    const std::size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string_view::npos);
    const std::uint8_t declared[4] = {0x54, 0x45, 0x53, 0x54};  // 1,413,829,460 bytes.
    std::copy(std::begin(declared), std::end(declared), png.begin() + std::ptrdiff_t(idat) - 4);
    auto decoded = decodeImage(png);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(decoded.error().message.find("declares 1413829460 bytes"), std::string::npos)
        << decoded.error().message;
}

TEST(ImageCodecTest, EmptyImageCannotBeEncoded) {
    EXPECT_FALSE(encodePng(ImageRgba8{}).ok());
}

// 16-bit greyscale PNGs decode (stb reduces them to 8 bits: the high byte) and say 16 bits in
// their header.
TEST(ImageCodecTest, Gray16RoundTripsThroughADecoder) {
    ImageGray16 image;
    image.width = 3;
    image.height = 2;
    image.pixels = {0x0000, 0x1234, 0xffff, 0x8000, 0x00ff, 0x7f01};
    auto encoded = encodePng16(image);
    ASSERT_TRUE(encoded.ok()) << encoded.error().message;
    EXPECT_EQ((*encoded)[24], 16);  // IHDR bit depth.
    EXPECT_EQ((*encoded)[25], 0);   // Greyscale.
    auto decoded = decodeImage(*encoded);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    ASSERT_EQ(decoded->width, 3u);
    ASSERT_EQ(decoded->height, 2u);
    const std::uint8_t expected[6] = {0x00, 0x12, 0xff, 0x80, 0x00, 0x7f};
    for (std::uint32_t i = 0; i < 6; ++i) {
        EXPECT_EQ(decoded->pixel(i % 3, i / 3)[0], expected[i]) << i;
        EXPECT_EQ(decoded->pixel(i % 3, i / 3)[3], 255);
    }
    EXPECT_FALSE(encodePng16(ImageGray16{}).ok());
}

// The encoder keeps its buffers per thread (PngScratch): images of other sizes and kinds in
// between, larger and smaller, leave nothing behind. The same image encodes to the same bytes
// every time, and each PNG is strictly valid and decodes to its own pixels.
TEST(ImageCodecTest, EncodingsInTurnOnOneThreadAreIndependent) {
    auto pattern = [](std::uint32_t width, std::uint32_t height, std::uint32_t seed) {
        ImageRgba8 image{width, height, ReusedBytes(std::size_t(width) * height * 4, 0)};
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            seed = seed * 1664525u + 1013904223u;
            image.pixels[i] = (i / 4) % 7 == 0 ? std::uint8_t(seed >> 24) : std::uint8_t(i / 64);
        }
        return image;
    };
    const ImageRgba8 large = pattern(640, 480, 1);
    const ImageRgba8 small = pattern(17, 5, 2);
    ImageGray16 depth{40, 30, std::vector<std::uint16_t>(40 * 30)};
    for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
        depth.pixels[i] = std::uint16_t(i * 977);
    }
    auto first = encodePng(large);
    ASSERT_TRUE(first.ok()) << first.error().message;
    auto smallPng = encodePng(small);
    auto depthPng = encodePng16(depth);
    auto again = encodePng(large);
    ASSERT_TRUE(smallPng.ok() && depthPng.ok() && again.ok());
    EXPECT_EQ(*again, *first);
    expectStrictlyValidPng(*first, (640 * 4 + 1) * 480);
    expectStrictlyValidPng(*smallPng, (17 * 4 + 1) * 5);
    expectStrictlyValidPng(*depthPng, (40 * 2 + 1) * 30);
    auto decodedSmall = decodeImage(*smallPng);
    ASSERT_TRUE(decodedSmall.ok()) << decodedSmall.error().message;
    EXPECT_EQ(decodedSmall->pixels, small.pixels);
    auto decodedLarge = decodeImage(*again);
    ASSERT_TRUE(decodedLarge.ok()) << decodedLarge.error().message;
    EXPECT_EQ(decodedLarge->pixels, large.pixels);
}

// runLengthZlib's streams inflate with zlib (which refuses incomplete or over-subscribed codes)
// to their data: no data, one byte, one repeated byte, random bytes (all literals), runs of
// every length around deflate's 258 and its 3-byte minimum, and frequencies in a Fibonacci
// sequence, whose Huffman code is 24 bits deep and must be limited to 15.
TEST(ImageCodecTest, RunLengthZlibInflatesToItsData) {
    std::vector<std::vector<std::uint8_t>> cases;
    cases.push_back({});
    cases.push_back({42});
    cases.push_back(std::vector<std::uint8_t>(1 << 20, 0));
    std::uint32_t seed = 7;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return seed >> 24;
    };
    std::vector<std::uint8_t> noise(100000);
    for (auto& byte : noise) {
        byte = std::uint8_t(random());
    }
    cases.push_back(noise);
    std::vector<std::uint8_t> runs;
    for (std::size_t length = 1; length <= 600; ++length) {
        runs.insert(runs.end(), length, std::uint8_t(length % 7));
    }
    cases.push_back(runs);
    std::vector<std::uint8_t> skewed;
    std::uint32_t previous = 1;
    std::uint32_t current = 1;
    for (std::uint8_t symbol = 0; symbol < 26; ++symbol) {
        skewed.insert(skewed.end(), current, symbol);
        const std::uint32_t next = previous + current;
        previous = current;
        current = next;
    }
    for (std::size_t i = skewed.size() - 1; i > 0; --i) {  // No long runs: shuffled.
        std::swap(skewed[i], skewed[random() % (i + 1)]);
    }
    cases.push_back(skewed);
    for (const auto& data : cases) {
        SCOPED_TRACE(data.size());
        std::vector<std::uint8_t> stream(runLengthZlibBound(data.size()));
        stream.resize(runLengthZlib(data, stream.data()));
        ASSERT_GT(stream.size(), 6u);
        std::vector<std::uint8_t> inflated(data.size() + 1);
        uLongf size = uLongf(inflated.size());
        ASSERT_EQ(uncompress(inflated.data(), &size, stream.data(), uLong(stream.size())), Z_OK);
        ASSERT_EQ(size, data.size());
        EXPECT_TRUE(std::equal(data.begin(), data.end(), inflated.begin()));
    }
}

// The IDAT data of `png` inflated: filter-type bytes and filtered rows.
std::vector<std::uint8_t> inflatedRows(const std::vector<std::uint8_t>& png, std::size_t rawBytes) {
    std::vector<std::uint8_t> idat;
    for (std::size_t offset = 8; offset + 12 <= png.size();) {
        const std::uint32_t length = std::uint32_t(png[offset]) << 24 |
                                     std::uint32_t(png[offset + 1]) << 16 |
                                     std::uint32_t(png[offset + 2]) << 8 | png[offset + 3];
        if (std::string_view(reinterpret_cast<const char*>(&png[offset + 4]), 4) == "IDAT") {
            idat.insert(idat.end(), &png[offset + 8], &png[offset + 8 + length]);
        }
        offset += 12 + length;
    }
    std::vector<std::uint8_t> raw(rawBytes);
    uLongf size = uLongf(raw.size());
    EXPECT_EQ(uncompress(raw.data(), &size, idat.data(), uLong(idat.size())), Z_OK);
    return raw;
}

// PngCompression::Small filters 8-bit rows with Paeth: undone here as the PNG specification
// writes it, every row gives back the pixels, for widths around the encoder's eight-byte steps
// and samples at the extremes (the predictor's sums need nine bits).
TEST(ImageCodecTest, SmallPngCompressionFiltersEightBitRowsWithPaeth) {
    std::uint32_t seed = 99;
    auto random = [&] {
        seed = seed * 1664525u + 1013904223u;
        return seed >> 24;
    };
    for (const std::uint32_t width : {1u, 2u, 3u, 7u, 37u, 130u}) {
        SCOPED_TRACE(width);
        const std::uint32_t height = 9;
        ImageRgba8 image{width, height, ReusedBytes(width * height * 4, 0)};
        for (std::uint32_t y = 0; y < height; ++y) {
            for (std::uint32_t x = 0; x < width; ++x) {
                std::uint8_t* p = image.pixel(x, y);
                p[0] = std::uint8_t(x * 7 + y * 3);  // Gradients.
                p[1] = std::uint8_t(random());       // Noise.
                p[2] = (x + y) % 3 == 0 ? 255 : 0;   // Extremes.
                p[3] = std::uint8_t(y < 4 ? 255 : random() & 0x81);
            }
        }
        auto png = encodePng(image, PngCompression::Small);
        ASSERT_TRUE(png.ok()) << png.error().message;
        const std::size_t rowBytes = width * 4;
        expectStrictlyValidPng(*png, (rowBytes + 1) * height);
        const std::vector<std::uint8_t> raw = inflatedRows(*png, (rowBytes + 1) * height);
        std::vector<std::uint8_t> pixels(rowBytes * height);
        for (std::uint32_t y = 0; y < height; ++y) {
            ASSERT_EQ(raw[y * (rowBytes + 1)], 4) << "row " << y << " is not Paeth-filtered";
            for (std::size_t i = 0; i < rowBytes; ++i) {
                const int a = i >= 4 ? pixels[y * rowBytes + i - 4] : 0;
                const int b = y > 0 ? pixels[(y - 1) * rowBytes + i] : 0;
                const int c = i >= 4 && y > 0 ? pixels[(y - 1) * rowBytes + i - 4] : 0;
                const int p = a + b - c;
                const int pa = std::abs(p - a);
                const int pb = std::abs(p - b);
                const int pc = std::abs(p - c);
                const int predicted = pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
                pixels[y * rowBytes + i] =
                    std::uint8_t(raw[y * (rowBytes + 1) + 1 + i] + predicted);
            }
        }
        EXPECT_EQ(pixels, image.pixels);
        auto decoded = decodeImage(*png);
        ASSERT_TRUE(decoded.ok()) << decoded.error().message;
        EXPECT_EQ(decoded->pixels, image.pixels);
    }
}

// PngCompression::Fast gives strictly valid PNGs of the same pixels.
TEST(ImageCodecTest, FastPngCompressionKeepsThePixels) {
    ImageRgba8 image{300, 200, ReusedBytes(300 * 200 * 4, 0)};
    for (std::uint32_t y = 40; y < 170; ++y) {
        for (std::uint32_t x = 60; x < 250; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t(x);
            p[1] = std::uint8_t(y * 2);
            p[2] = std::uint8_t((x * y) >> 6);
            p[3] = 255;
        }
    }
    auto small = encodePng(image);
    auto fast = encodePng(image, PngCompression::Fast);
    ASSERT_TRUE(small.ok() && fast.ok());
    EXPECT_NE(*fast, *small);
    expectStrictlyValidPng(*fast, (300 * 4 + 1) * 200);
    auto decoded = decodeImage(*fast);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->pixels, image.pixels);
    ImageGray16 depth{40, 30, std::vector<std::uint16_t>(40 * 30)};
    for (std::size_t i = 0; i < depth.pixels.size(); ++i) {
        depth.pixels[i] = std::uint16_t(i * 977);
    }
    auto depthPng = encodePng16(depth, PngCompression::Fast);
    ASSERT_TRUE(depthPng.ok());
    expectStrictlyValidPng(*depthPng, (40 * 2 + 1) * 30);
}

}  // namespace
}  // namespace encore::image
