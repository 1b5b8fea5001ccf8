// decodeImage against stb_image, the decoder it replaced for PNG and JPEG: PNGs of every colour
// type and bit depth decode to stb's pixels exactly, JPEGs within libjpeg-turbo's rounding, and
// corrupt or truncated files are errors that name the problem (libjpeg's default handler would
// have called exit()).

#include <gtest/gtest.h>

#include <cstdio>  // Before jpeglib.h, which uses FILE and size_t without including them.

#include <jpeglib.h>
#include <stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "TestPaths.h"
#include "TextureFixtures.h"
#include "core/FileIO.h"
#include "encore/image/ImageCodec.h"
#include "image/ImageDecoders.h"

namespace encore::image {
namespace {

using Bytes = std::vector<std::uint8_t>;

void appendBigEndian(Bytes& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) {
        out.push_back(std::uint8_t(value >> shift));
    }
}

void appendChunk(Bytes& png, const char* type, const Bytes& data) {
    appendBigEndian(png, std::uint32_t(data.size()));
    const std::size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    appendBigEndian(png, std::uint32_t(crc32(0, png.data() + start, uInt(png.size() - start))));
}

int paeth(int left, int above, int upperLeft) {
    const int estimate = left + above - upperLeft;
    const int toLeft = std::abs(estimate - left);
    const int toAbove = std::abs(estimate - above);
    const int toUpperLeft = std::abs(estimate - upperLeft);
    if (toLeft <= toAbove && toLeft <= toUpperLeft) {
        return left;
    }
    return toAbove <= toUpperLeft ? above : upperLeft;
}

// Appends `rows` (unfiltered scanlines of `rowBytes`) to `out`, filtered with the five PNG
// filters in turn so that the decoders undo all of them.
void appendFiltered(Bytes& out, const std::vector<Bytes>& rows, std::size_t bytesPerPixel) {
    const Bytes zeros(rows.empty() ? 0 : rows[0].size(), 0);
    for (std::size_t y = 0; y < rows.size(); ++y) {
        const Bytes& row = rows[y];
        const Bytes& above = y == 0 ? zeros : rows[y - 1];
        const std::uint8_t filter = std::uint8_t(y % 5);
        out.push_back(filter);
        for (std::size_t i = 0; i < row.size(); ++i) {
            const int left = i >= bytesPerPixel ? row[i - bytesPerPixel] : 0;
            const int upperLeft = i >= bytesPerPixel ? above[i - bytesPerPixel] : 0;
            const int predicted = filter == 0   ? 0
                                  : filter == 1 ? left
                                  : filter == 2 ? above[i]
                                  : filter == 3 ? (left + above[i]) / 2
                                                : paeth(left, above[i], upperLeft);
            out.push_back(std::uint8_t(row[i] - predicted));
        }
    }
}

struct PngCase {
    std::uint8_t colorType;  // 0 grey, 2 RGB, 3 palette, 4 grey-alpha, 6 RGBA.
    std::uint8_t bitDepth;
    bool transparencyChunk;  // tRNS: palette alphas, or the grey or RGB colour key.
    bool interlaced;         // Adam7.
};

std::string describe(const PngCase& c) {
    return "colour type " + std::to_string(c.colorType) + ", " + std::to_string(c.bitDepth) +
           " bits" + (c.transparencyChunk ? ", tRNS" : "") + (c.interlaced ? ", Adam7" : "");
}

// A PNG of random samples drawn from a few values (so that colour keys match some pixels).
Bytes makePng(const PngCase& c, std::uint32_t width, std::uint32_t height, unsigned seed) {
    std::mt19937 random(seed);
    const std::uint32_t channels = c.colorType == 0 || c.colorType == 3 ? 1
                                   : c.colorType == 4                   ? 2
                                   : c.colorType == 2                   ? 3
                                                                        : 4;
    const std::uint32_t bitsPerPixel = channels * c.bitDepth;
    const std::size_t bytesPerPixel = std::max<std::uint32_t>(1, bitsPerPixel / 8);
    // Every sample value is one of four, except for palette indices: all of the palette.
    const std::uint32_t maxSample = (1u << c.bitDepth) - 1;
    const std::uint32_t values[4] = {0, maxSample / 3, maxSample, maxSample / 2 + 1};
    const auto sample = [&] {
        return c.colorType == 3 ? std::uint32_t(random() % (maxSample + 1)) : values[random() % 4];
    };
    const auto makeRows = [&](std::uint32_t passWidth, std::uint32_t passHeight) {
        std::vector<Bytes> rows(passHeight, Bytes((std::size_t(passWidth) * bitsPerPixel + 7) / 8));
        for (Bytes& row : rows) {
            for (std::uint32_t s = 0; s < passWidth * channels; ++s) {
                const std::uint32_t value = sample();
                if (c.bitDepth == 16) {
                    row[s * 2] = std::uint8_t(value >> 8);
                    row[s * 2 + 1] = std::uint8_t(value);
                } else {
                    const std::size_t bit = std::size_t(s) * c.bitDepth;
                    row[bit / 8] |= std::uint8_t(value << (8 - c.bitDepth - bit % 8));
                }
            }
        }
        return rows;
    };
    Bytes scanlines;
    if (!c.interlaced) {
        appendFiltered(scanlines, makeRows(width, height), bytesPerPixel);
    } else {
        static constexpr std::uint32_t kStartX[7] = {0, 4, 0, 2, 0, 1, 0};
        static constexpr std::uint32_t kStartY[7] = {0, 0, 4, 0, 2, 0, 1};
        static constexpr std::uint32_t kStepX[7] = {8, 8, 4, 4, 2, 2, 1};
        static constexpr std::uint32_t kStepY[7] = {8, 8, 8, 4, 4, 2, 2};
        for (int pass = 0; pass < 7; ++pass) {
            const std::uint32_t passWidth =
                (width + kStepX[pass] - kStartX[pass] - 1) / kStepX[pass];
            const std::uint32_t passHeight =
                (height + kStepY[pass] - kStartY[pass] - 1) / kStepY[pass];
            if (passWidth > 0 && passHeight > 0) {
                appendFiltered(scanlines, makeRows(passWidth, passHeight), bytesPerPixel);
            }
        }
    }
    uLongf compressedSize = compressBound(uLong(scanlines.size()));
    Bytes compressed(compressedSize);
    EXPECT_EQ(
        compress2(compressed.data(), &compressedSize, scanlines.data(), uLong(scanlines.size()), 6),
        Z_OK);
    compressed.resize(compressedSize);

    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    Bytes header;
    appendBigEndian(header, width);
    appendBigEndian(header, height);
    header.insert(header.end(), {c.bitDepth, c.colorType, 0, 0, std::uint8_t(c.interlaced)});
    appendChunk(png, "IHDR", header);
    if (c.colorType == 3) {
        Bytes palette(3 * (std::size_t(maxSample) + 1));
        std::generate(palette.begin(), palette.end(), [&] { return std::uint8_t(random()); });
        appendChunk(png, "PLTE", palette);
    }
    if (c.transparencyChunk) {
        Bytes transparency;
        if (c.colorType == 3) {
            transparency.resize(std::max<std::size_t>(1, maxSample / 2));  // Fewer than colours.
            std::generate(transparency.begin(), transparency.end(),
                          [&] { return std::uint8_t(random()); });
        } else {
            // The key: values[1] in each channel, 16 bits big-endian whatever the bit depth.
            for (std::uint32_t channel = 0; channel < channels; ++channel) {
                transparency.push_back(std::uint8_t(values[1] >> 8));
                transparency.push_back(std::uint8_t(values[1]));
            }
        }
        appendChunk(png, "tRNS", transparency);
    }
    appendChunk(png, "IDAT", compressed);
    appendChunk(png, "IEND", {});
    return png;
}

struct StbiFree {
    void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

Bytes decodeWithStb(const Bytes& encoded, int& width, int& height) {
    int channels = 0;
    std::unique_ptr<stbi_uc, StbiFree> pixels(
        stbi_load_from_memory(encoded.data(), int(encoded.size()), &width, &height, &channels, 4));
    if (!pixels) {
        return {};
    }
    return Bytes(pixels.get(), pixels.get() + std::size_t(width) * height * 4);
}

TEST(ImageDecodersTest, PngEqualsStbForEveryColourTypeAndBitDepth) {
    std::vector<PngCase> cases;
    for (const bool interlaced : {false, true}) {
        for (const std::uint8_t depth : {1, 2, 4, 8, 16}) {
            for (const bool transparency : {false, true}) {
                cases.push_back({0, depth, transparency, interlaced});
                if (depth >= 8) {
                    cases.push_back({2, depth, transparency, interlaced});
                    cases.push_back({4, depth, false, interlaced});
                    cases.push_back({6, depth, false, interlaced});
                }
                if (depth <= 8) {
                    cases.push_back({3, depth, transparency, interlaced});
                }
            }
        }
    }
    unsigned seed = 1;
    for (const PngCase& c : cases) {
        for (const auto& [width, height] : {std::pair{1u, 1u}, {13u, 7u}, {37u, 29u}}) {
            const Bytes png = makePng(c, width, height, seed++);
            int stbWidth = 0;
            int stbHeight = 0;
            const Bytes expected = decodeWithStb(png, stbWidth, stbHeight);
            ASSERT_FALSE(expected.empty()) << describe(c) << ": " << stbi_failure_reason();
            auto decoded = decodeImage(png);
            ASSERT_TRUE(decoded.ok()) << describe(c) << ": " << decoded.error().message;
            EXPECT_EQ(decoded->width, width) << describe(c);
            EXPECT_EQ(decoded->height, height) << describe(c);
            EXPECT_TRUE(decoded->pixels == expected)
                << describe(c) << ", " << width << "x" << height;
        }
    }
}

// decodePng's fast path (libdeflate) takes every 8-bit, non-interlaced PNG, with all five
// filters, palettes and tRNS keys, and gives stb's pixels; it leaves the other depths and
// Adam7 to libspng. IDAT data split over several chunks decodes the same, and so does a stream
// whose Adler-32 is wrong: the fast path refuses it and libspng ignores the checksum.
TEST(ImageDecodersTest, LibdeflatePathTakesEightBitPngsAndEqualsStb) {
    unsigned seed = 100;
    for (const bool interlaced : {false, true}) {
        for (const std::uint8_t depth : {4, 8, 16}) {
            for (const std::uint8_t colorType : {0, 2, 3, 4, 6}) {
                if ((colorType == 3 && depth == 16) ||
                    (colorType != 0 && colorType != 3 && depth < 8)) {
                    continue;
                }
                for (const bool transparency : {false, true}) {
                    if (transparency && (colorType == 4 || colorType == 6)) {
                        continue;
                    }
                    const PngCase c{colorType, depth, transparency, interlaced};
                    const Bytes png = makePng(c, 37, 29, seed++);
                    const std::optional<ImageRgba8> fast = decodePngWithLibdeflate(png);
                    if (depth != 8 || interlaced) {
                        EXPECT_FALSE(fast.has_value()) << describe(c);
                        continue;
                    }
                    ASSERT_TRUE(fast.has_value()) << describe(c);
                    int width = 0;
                    int height = 0;
                    EXPECT_TRUE(fast->pixels == decodeWithStb(png, width, height)) << describe(c);
                }
            }
        }
    }

    const Bytes png = makePng({6, 8, false, false}, 37, 29, 5);
    const auto expected = decodePngWithLibdeflate(png);
    ASSERT_TRUE(expected.has_value());
    // The IDAT chunk starts after the signature and IHDR (33 bytes); IEND is the last 12.
    const std::size_t idatLength = png.size() - 33 - 12 - 12;
    const Bytes idat(png.begin() + 33 + 8, png.begin() + 33 + 8 + std::ptrdiff_t(idatLength));
    Bytes split(png.begin(), png.begin() + 33);
    const std::size_t third = idatLength / 3;
    appendChunk(split, "IDAT", Bytes(idat.begin(), idat.begin() + std::ptrdiff_t(third)));
    const auto middle = idat.begin() + std::ptrdiff_t(third);
    appendChunk(split, "IDAT", Bytes(middle, middle + std::ptrdiff_t(third)));
    appendChunk(split, "IDAT", Bytes(idat.begin() + std::ptrdiff_t(2 * third), idat.end()));
    appendChunk(split, "IEND", {});
    const auto joined = decodePngWithLibdeflate(split);
    ASSERT_TRUE(joined.has_value());
    EXPECT_TRUE(joined->pixels == expected->pixels);

    Bytes badChecksum(png.begin(), png.begin() + 33);
    Bytes corrupted = idat;
    corrupted.back() ^= 0x5a;  // The Adler-32's last byte.
    appendChunk(badChecksum, "IDAT", corrupted);
    appendChunk(badChecksum, "IEND", {});
    EXPECT_FALSE(decodePngWithLibdeflate(badChecksum).has_value());
    auto decoded = decodeImage(badChecksum);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_TRUE(decoded->pixels == expected->pixels);
}

// Malformed ancillary chunks (metadata) are ignored, as stb_image ignored them: such files
// still decode, to the same pixels.
TEST(ImageDecodersTest, MalformedAncillaryChunksAreIgnored) {
    const Bytes png = makePng({2, 8, false, false}, 13, 7, 3);
    Bytes chunks;
    appendChunk(chunks, "tEXt", {0, 'n', 'o', ' ', 'k', 'e', 'y'});  // An empty keyword.
    appendChunk(chunks, "gAMA", {0, 0, 0, 0});                       // Gamma 0.
    appendChunk(chunks, "pHYs", {0, 0, 0, 1});                       // 4 of 9 bytes.
    appendChunk(chunks, "iCCP", {'p', 0, 0, 1, 2, 3});               // Not zlib data.
    Bytes withChunks(png.begin(), png.begin() + 33);                 // Signature and IHDR.
    withChunks.insert(withChunks.end(), chunks.begin(), chunks.end());
    withChunks.insert(withChunks.end(), png.begin() + 33, png.end());
    auto expected = decodeImage(png);
    ASSERT_TRUE(expected.ok()) << expected.error().message;
    auto decoded = decodeImage(withChunks);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_TRUE(decoded->pixels == expected->pixels);
}

// Every prefix of a PNG that cuts into its pixels is an error, never a crash or a partial image.
// (One that lacks only the IEND chunk holds all of them and decodes, with stb_image too.)
TEST(ImageDecodersTest, TruncatedPngIsAnError) {
    const Bytes png = makePng({6, 8, false, false}, 37, 29, 7);
    ASSERT_TRUE(decodeImage(png).ok());
    const std::size_t iendBytes = 12;
    for (std::size_t length = 1; length < png.size() - iendBytes; ++length) {
        const Bytes truncated(png.begin(), png.begin() + std::ptrdiff_t(length));
        auto decoded = decodeImage(truncated);
        ASSERT_FALSE(decoded.ok()) << length << " of " << png.size() << " bytes";
        EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
        EXPECT_FALSE(decoded.error().message.empty());
    }
}

// A JPEG of smooth gradients and a hard edge, in `color` (JCS_RGB, JCS_GRAYSCALE or JCS_CMYK,
// stored as such).
Bytes encodeJpeg(std::uint32_t width,
                 std::uint32_t height,
                 bool progressive,
                 J_COLOR_SPACE color = JCS_RGB) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &buffer, &size);
    info.image_width = width;
    info.image_height = height;
    info.input_components = color == JCS_GRAYSCALE ? 1 : color == JCS_CMYK ? 4 : 3;
    info.in_color_space = color;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 90, TRUE);
    if (progressive) {
        jpeg_simple_progression(&info);
    }
    jpeg_start_compress(&info, TRUE);
    const std::size_t channels = std::size_t(info.input_components);
    Bytes row(std::size_t(width) * channels);
    while (info.next_scanline < height) {
        for (std::uint32_t x = 0; x < width; ++x) {
            const std::uint8_t values[4] = {std::uint8_t(x * 255 / width),
                                            std::uint8_t(info.next_scanline * 255 / height),
                                            std::uint8_t(x < width / 2 ? 40 : 220), 30};
            std::copy(values, values + channels, &row[x * channels]);
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

int maxDifference(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
    int difference = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        difference = std::max(difference, std::abs(int(a[i]) - int(b[i])));
    }
    return difference;
}

// libjpeg-turbo's IDCT and upsampling round differently from stb's: within 3 levels on the
// shared models' 2048x2048 JPEGs.
TEST(ImageDecodersTest, JpegIsCloseToStb) {
    for (const bool progressive : {false, true}) {
        const Bytes jpeg = encodeJpeg(67, 45, progressive);
        int width = 0;
        int height = 0;
        const Bytes expected = decodeWithStb(jpeg, width, height);
        auto decoded = decodeImage(jpeg);
        ASSERT_TRUE(decoded.ok()) << decoded.error().message;
        ASSERT_EQ(decoded->width, 67u);
        ASSERT_EQ(decoded->height, 45u);
        ASSERT_EQ(decoded->pixels.size(), expected.size());
        EXPECT_LE(maxDifference(decoded->pixels, expected), 3) << progressive;
        for (std::size_t i = 3; i < decoded->pixels.size(); i += 4) {
            ASSERT_EQ(decoded->pixels[i], 255);
        }
    }
}

// Greyscale JPEGs become grey RGBA; CMYK ones, which libjpeg-turbo cannot convert to RGBA, are
// decoded by stb_image as before.
TEST(ImageDecodersTest, GreyAndCmykJpegsDecode) {
    for (const J_COLOR_SPACE color : {JCS_GRAYSCALE, JCS_CMYK}) {
        const Bytes jpeg = encodeJpeg(33, 21, false, color);
        int width = 0;
        int height = 0;
        const Bytes expected = decodeWithStb(jpeg, width, height);
        ASSERT_FALSE(expected.empty()) << color;
        auto decoded = decodeImage(jpeg);
        ASSERT_TRUE(decoded.ok()) << decoded.error().message;
        ASSERT_EQ(decoded->pixels.size(), expected.size());
        EXPECT_LE(maxDifference(decoded->pixels, expected), color == JCS_CMYK ? 0 : 3) << color;
        if (color == JCS_GRAYSCALE) {
            for (std::size_t i = 0; i < decoded->pixels.size(); i += 4) {
                ASSERT_EQ(decoded->pixels[i], decoded->pixels[i + 1]);
                ASSERT_EQ(decoded->pixels[i], decoded->pixels[i + 2]);
                ASSERT_EQ(decoded->pixels[i + 3], 255);
            }
        }
    }
}

TEST(ImageDecodersTest, SharedJpegsAreCloseToStb) {
    const auto models = test::sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "../shared/models is absent";
    }
    for (const char* name : {"CesiumMilkTruck/glTF/CesiumMilkTruck.jpg",
                             "AlphaBlendModeTest/glTF/MatBed_baseColor.jpg"}) {
        auto bytes = readFile(*models / name);
        ASSERT_TRUE(bytes.ok()) << bytes.error().message;
        int width = 0;
        int height = 0;
        const Bytes expected = decodeWithStb(*bytes, width, height);
        auto decoded = decodeImage(*bytes);
        ASSERT_TRUE(decoded.ok()) << decoded.error().message;
        ASSERT_EQ(decoded->pixels.size(), expected.size());
        EXPECT_LE(maxDifference(decoded->pixels, expected), 3) << name;
    }
}

// Corrupt JPEGs come back as errors naming the problem instead of libjpeg calling exit().
TEST(ImageDecodersTest, CorruptJpegIsAnError) {
    const Bytes garbage = {0xff, 0xd8, 0xff, 0x00, 1, 2, 3, 4, 5, 6, 7, 8};
    auto decoded = decodeImage(garbage);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(decoded.error().message.find("not a decodable JPEG"), std::string::npos)
        << decoded.error().message;

    // A frame header (SOF) declaring 0 lines.
    Bytes jpeg = encodeJpeg(16, 16, false);
    for (std::size_t i = 2; i + 8 < jpeg.size(); ++i) {
        if (jpeg[i] == 0xff && jpeg[i + 1] == 0xc0) {
            jpeg[i + 5] = 0;
            jpeg[i + 6] = 0;
            break;
        }
    }
    decoded = decodeImage(jpeg);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(decoded.error().message.find("JPEG"), std::string::npos) << decoded.error().message;
}

// A progressive JPEG repeating its last scan hundreds of times (each one a pass over every
// coefficient) is refused once it passes the scan limit.
TEST(ImageDecodersTest, JpegWithTooManyScansIsAnError) {
    const Bytes jpeg = encodeJpeg(16, 16, true);
    std::size_t lastScan = 0;
    for (std::size_t i = 0; i + 1 < jpeg.size(); ++i) {
        if (jpeg[i] == 0xff && jpeg[i + 1] == 0xda) {
            lastScan = i;
        }
    }
    ASSERT_GT(lastScan, 0u);
    ASSERT_EQ(jpeg[jpeg.size() - 2], 0xff);  // EOI.
    const Bytes scan(jpeg.begin() + std::ptrdiff_t(lastScan), jpeg.end() - 2);
    Bytes repeated(jpeg.begin(), jpeg.end() - 2);
    for (int copy = 0; copy < 600; ++copy) {
        repeated.insert(repeated.end(), scan.begin(), scan.end());
    }
    repeated.insert(repeated.end(), {0xff, 0xd9});
    auto decoded = decodeImage(repeated);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().message.find("progressive scans"), std::string::npos)
        << decoded.error().message;
}

// Every prefix of a JPEG returns: an error, or an image of the declared size (libjpeg fills
// what is missing, as stb_image did), and never exits the process.
TEST(ImageDecodersTest, TruncatedJpegReturns) {
    const Bytes jpeg = encodeJpeg(40, 24, true);
    for (std::size_t length = 3; length < jpeg.size(); length += 7) {
        const Bytes truncated(jpeg.begin(), jpeg.begin() + std::ptrdiff_t(length));
        auto decoded = decodeImage(truncated);
        if (decoded.ok()) {
            EXPECT_EQ(decoded->pixels.size(), 40u * 24u * 4u);
        } else {
            EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
            EXPECT_NE(decoded.error().message.find("JPEG"), std::string::npos)
                << decoded.error().message;
        }
    }
}

// WebP (EXT_texture_webp) through libwebp: a lossless image with varying colour and alpha
// decodes to its exact pixels, and a WebP image is told from the other formats by its header.
TEST(ImageDecodersTest, LosslessWebpDecodesExactly) {
    ImageRgba8 source;
    source.width = 37;
    source.height = 11;
    for (std::uint32_t y = 0; y < source.height; ++y) {
        for (std::uint32_t x = 0; x < source.width; ++x) {
            // Alpha 0 keeps its colour: libwebp's lossless encoder is exact by default.
            source.pixels.insert(source.pixels.end(),
                                 {std::uint8_t(x * 7), std::uint8_t(y * 23), std::uint8_t(x ^ y),
                                  std::uint8_t(255 - x * 3)});
        }
    }
    const Bytes webp = test::encodeWebpBytes(source, /*lossless=*/true);
    ASSERT_TRUE(isWebp(webp));
    EXPECT_FALSE(isPng(webp));
    auto decoded = decodeImage(webp);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->width, source.width);
    EXPECT_EQ(decoded->height, source.height);
    EXPECT_EQ(decoded->pixels, source.pixels);
}

// Every prefix of a WebP file returns an error naming WebP, or the image of the declared size.
TEST(ImageDecodersTest, TruncatedWebpReturns) {
    const Bytes webp = test::encodeWebpBytes(test::solidImage({1, 2, 3, 255}, 16, 16), false);
    for (std::size_t length = 12; length < webp.size(); length += 5) {
        const Bytes truncated(webp.begin(), webp.begin() + std::ptrdiff_t(length));
        auto decoded = decodeImage(truncated);
        if (decoded.ok()) {
            EXPECT_EQ(decoded->pixels.size(), 16u * 16u * 4u);
        } else {
            EXPECT_EQ(decoded.error().code, ErrorCode::InvalidFormat);
            EXPECT_NE(decoded.error().message.find("WebP"), std::string::npos)
                << decoded.error().message;
        }
    }
}

}  // namespace
}  // namespace encore::image
