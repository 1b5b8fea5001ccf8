#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "TestPaths.h"
#include "core/FileIO.h"
#include "encore/image/HdrImage.h"

namespace encore::image {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Radiance's shared-exponent encoding, written here rather than with stb so the test checks
// the decoder against the format, not against stb's own writer.
std::array<std::uint8_t, 4> toRgbe(float r, float g, float b) {
    const float largest = std::max({r, g, b});
    if (largest < 1e-32f) {
        return {0, 0, 0, 0};
    }
    int exponent = 0;
    const float scale = std::frexp(largest, &exponent) * 256.0f / largest;
    return {static_cast<std::uint8_t>(r * scale), static_cast<std::uint8_t>(g * scale),
            static_cast<std::uint8_t>(b * scale), static_cast<std::uint8_t>(exponent + 128)};
}

void appendText(Bytes& bytes, const std::string& text) {
    bytes.insert(bytes.end(), text.begin(), text.end());
}

Bytes header(std::uint32_t width, std::uint32_t height) {
    Bytes bytes;
    appendText(bytes, "#?RADIANCE\n# made by HdrImageTest\nFORMAT=32-bit_rle_rgbe\n\n");
    appendText(bytes, "-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n");
    return bytes;
}

// Flat scanlines: four bytes per pixel, as old writers and narrow images use.
Bytes flatHdr(const HdrImage& image) {
    Bytes bytes = header(image.width, image.height);
    for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
        const auto rgbe = toRgbe(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]);
        bytes.insert(bytes.end(), rgbe.begin(), rgbe.end());
    }
    return bytes;
}

// Adaptive RLE scanlines (2, 2, width >> 8, width & 255, then each component run-length coded
// on its own): runs of three or more equal bytes become runs, the rest literal dumps.
Bytes rleHdr(const HdrImage& image) {
    Bytes bytes = header(image.width, image.height);
    std::vector<std::uint8_t> component(image.width);
    for (std::uint32_t y = 0; y < image.height; ++y) {
        bytes.insert(bytes.end(), {2, 2, static_cast<std::uint8_t>(image.width >> 8),
                                   static_cast<std::uint8_t>(image.width & 255)});
        std::vector<std::array<std::uint8_t, 4>> pixels;
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const float* p = &image.rgb[(std::size_t(y) * image.width + x) * 3];
            pixels.push_back(toRgbe(p[0], p[1], p[2]));
        }
        for (int c = 0; c < 4; ++c) {
            for (std::uint32_t x = 0; x < image.width; ++x) {
                component[x] = pixels[x][c];
            }
            std::uint32_t x = 0;
            while (x < image.width) {
                std::uint32_t run = 1;
                while (x + run < image.width && run < 127 && component[x + run] == component[x]) {
                    ++run;
                }
                if (run >= 3) {
                    bytes.push_back(static_cast<std::uint8_t>(128 + run));
                    bytes.push_back(component[x]);
                    x += run;
                    continue;
                }
                // A literal dump up to the next run of three (or 128 bytes).
                std::uint32_t end = x;
                while (end < image.width && end - x < 128 &&
                       !(end + 2 < image.width && component[end] == component[end + 1] &&
                         component[end] == component[end + 2])) {
                    ++end;
                }
                end = std::max(end, x + 1);
                bytes.push_back(static_cast<std::uint8_t>(end - x));
                bytes.insert(bytes.end(), component.begin() + x, component.begin() + end);
                x = end;
            }
        }
    }
    return bytes;
}

// Values whose RGBE encoding is exact (powers of two times small integers), with runs of equal
// pixels so RLE has something to compress.
HdrImage testImage(std::uint32_t width, std::uint32_t height) {
    HdrImage image{width, height, {}};
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const float base = x < width / 2 ? 1.0f : 0.25f * float(1 + (x % 4));
            image.rgb.insert(image.rgb.end(), {base, base * 0.5f, float(y + 1) * 8.0f});
        }
    }
    return image;
}

void expectSamePixels(const HdrImage& decoded, const HdrImage& expected) {
    ASSERT_EQ(decoded.width, expected.width);
    ASSERT_EQ(decoded.height, expected.height);
    ASSERT_EQ(decoded.rgb.size(), expected.rgb.size());
    for (std::size_t i = 0; i < expected.rgb.size(); i += 3) {
        // RGBE keeps 8 bits of mantissa relative to the pixel's largest channel.
        const float largest = std::max({expected.rgb[i], expected.rgb[i + 1], expected.rgb[i + 2]});
        for (std::size_t c = i; c < i + 3; ++c) {
            EXPECT_NEAR(decoded.rgb[c], expected.rgb[c], largest / 128.0f) << "float " << c;
        }
    }
}

TEST(HdrImageTest, DecodesFlatScanlines) {
    const HdrImage expected = testImage(5, 3);
    auto decoded = decodeHdr(flatHdr(expected));
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    expectSamePixels(*decoded, expected);
    // A pixel whose channels are all exact in RGBE: (1, 0.5, 8) with exponent 4.
    EXPECT_FLOAT_EQ(decoded->rgb[0], 1.0f);
    EXPECT_FLOAT_EQ(decoded->rgb[1], 0.5f);
    EXPECT_FLOAT_EQ(decoded->rgb[2], 8.0f);
}

TEST(HdrImageTest, DecodesRunLengthEncodedScanlines) {
    const HdrImage expected = testImage(40, 4);  // RLE applies to widths 8..32767.
    const Bytes encoded = rleHdr(expected);
    EXPECT_LT(encoded.size(), flatHdr(expected).size());
    auto decoded = decodeHdr(encoded);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    expectSamePixels(*decoded, expected);
}

TEST(HdrImageTest, RefusesDataThatIsNotHdr) {
    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13};
    auto decoded = decodeHdr(png);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(decoded.error().message.find("not a Radiance HDR"), std::string::npos)
        << decoded.error().message;

    EXPECT_FALSE(decodeHdr(Bytes{}).ok());
}

TEST(HdrImageTest, RefusesTruncatedPixels) {
    // stb alone would loop forever here: past the end it reads zeros, a dump of length 0.
    const Bytes bytes = rleHdr(testImage(40, 4));
    for (std::size_t cut : {std::size_t(1), std::size_t(30), std::size_t(100), bytes.size() / 2}) {
        const Bytes truncated(bytes.begin(), bytes.end() - static_cast<std::ptrdiff_t>(cut));
        auto decoded = decodeHdr(truncated);
        ASSERT_FALSE(decoded.ok()) << "cut " << cut;
        EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
        EXPECT_NE(decoded.error().message.find("truncated"), std::string::npos)
            << decoded.error().message;
    }
}

TEST(HdrImageTest, RefusesZeroLengthRuns) {
    Bytes bytes = header(8, 1);
    bytes.insert(bytes.end(), {2, 2, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0});
    auto decoded = decodeHdr(bytes);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
}

TEST(HdrImageTest, RefusesAbsurdSizesBeforeDecoding) {
    Bytes bytes = header(100000, 2);
    bytes.resize(bytes.size() + 64, 0);
    auto decoded = decodeHdr(bytes);
    ASSERT_FALSE(decoded.ok());
    // stb itself may refuse the header first; ours names the size.
    EXPECT_TRUE(decoded.error().code == ErrorCode::LimitExceeded ||
                decoded.error().code == ErrorCode::InvalidFormat);
    EXPECT_NE(decoded.error().message.find("100000"), std::string::npos) << decoded.error().message;
}

TEST(HdrImageTest, MissingFileIsNamed) {
    const auto path = test::makeTempDir("hdr") / "missing.hdr";
    auto read = readHdr(path);
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::FileNotFound);
    EXPECT_NE(read.error().message.find("missing.hdr"), std::string::npos);
}

TEST(HdrImageTest, BadFileIsNamed) {
    const auto path = test::makeTempDir("hdr") / "garbage.hdr";
    const Bytes garbage = {'n', 'o', 't', ' ', 'h', 'd', 'r'};
    ASSERT_TRUE(writeFile(path, garbage).ok());
    auto read = readHdr(path);
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(read.error().message.find("garbage.hdr"), std::string::npos);
}

TEST(HdrImageTest, ReadsAFileItWrote) {
    const auto path = test::makeTempDir("hdr") / "image.hdr";
    const HdrImage expected = testImage(16, 8);
    ASSERT_TRUE(writeFile(path, rleHdr(expected)).ok());
    auto read = readHdr(path);
    ASSERT_TRUE(read.ok()) << read.error().message;
    expectSamePixels(*read, expected);
}

void expectFinitePositivePanorama(const HdrImage& image, std::uint32_t width) {
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, width / 2);
    ASSERT_EQ(image.rgb.size(), std::size_t(image.width) * image.height * 3);
    for (float value : image.rgb) {
        ASSERT_TRUE(std::isfinite(value));
        ASSERT_GT(value, 0.0f);
    }
}

TEST(HdrImageTest, StudioEnvironmentHasTheDocumentedShape) {
    const HdrImage studio = makeStudioEnvironment();
    expectFinitePositivePanorama(studio, 512);
    expectFinitePositivePanorama(makeStudioEnvironment(128), 128);

    auto at = [&](std::uint32_t x, std::uint32_t y, int c) {
        return studio.rgb[(std::size_t(y) * studio.width + x) * 3 + c];
    };
    auto luminance = [&](std::uint32_t x, std::uint32_t y) {
        return 0.2126f * at(x, y, 0) + 0.7152f * at(x, y, 1) + 0.0722f * at(x, y, 2);
    };
    // Sky brighter upward (away from the sun's longitude), the ground darker and warm.
    const std::uint32_t column = studio.width * 3 / 4;
    EXPECT_GT(luminance(column, 5), luminance(column, studio.height / 2 - 20));
    const std::uint32_t groundRow = studio.height * 3 / 4;
    EXPECT_LT(luminance(column, groundRow), luminance(column, studio.height / 2 - 20));
    EXPECT_GT(at(column, groundRow, 0), at(column, groundRow, 2));
    // The sun is the brightest thing and lies in the upper half.
    float brightest = 0.0f;
    std::uint32_t brightestRow = 0;
    for (std::uint32_t y = 0; y < studio.height; ++y) {
        for (std::uint32_t x = 0; x < studio.width; ++x) {
            if (luminance(x, y) > brightest) {
                brightest = luminance(x, y);
                brightestRow = y;
            }
        }
    }
    EXPECT_GT(brightest, 50.0f);
    EXPECT_LT(brightestRow, studio.height / 3);
    // Box lights toward +X (column 0, phi ~ 0) and -X (the middle column, phi ~ pi), just above
    // the horizon.
    const std::uint32_t boxRow = studio.height / 2 - studio.height / 16;
    EXPECT_GT(luminance(0, boxRow), 3.0f);
    EXPECT_GT(luminance(studio.width / 2, boxRow), 3.0f);
}

TEST(HdrImageTest, UniformEnvironmentIsConstant) {
    const HdrImage uniform = makeUniformEnvironment(1.0f, 0.5f, 0.25f);
    expectFinitePositivePanorama(uniform, 64);
    for (std::size_t i = 0; i < uniform.rgb.size(); i += 3) {
        ASSERT_EQ(uniform.rgb[i], 1.0f);
        ASSERT_EQ(uniform.rgb[i + 1], 0.5f);
        ASSERT_EQ(uniform.rgb[i + 2], 0.25f);
    }
    expectFinitePositivePanorama(makeUniformEnvironment(2.0f, 2.0f, 2.0f, 16), 16);
}

TEST(HdrImageTest, SharedReferenceStudioDecodes) {
    const auto models = test::sharedModelsDir();
    const auto path = models ? models->parent_path() / "reference" / "studio.hdr"
                             : std::filesystem::path("../shared/reference/studio.hdr");
    if (!std::filesystem::exists(path)) {
        GTEST_SKIP() << path << " is absent";
    }
    auto read = readHdr(path);
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->width, 512u);
    EXPECT_EQ(read->height, 256u);
    for (float value : read->rgb) {
        ASSERT_TRUE(std::isfinite(value));
        ASSERT_GE(value, 0.0f);
    }
}

}  // namespace
}  // namespace encore::image
