// encore compare: SSIM and colour error of two PNGs, the side-by-side picture, and the errors for
// unreadable files and different sizes.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

image::ImageRgba8 flat(std::uint32_t width, std::uint32_t height, std::uint8_t grey) {
    image::ImageRgba8 image;
    image.width = width;
    image.height = height;
    image.pixels.assign(std::size_t(width) * height * 4, grey);
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
        image.pixels[i] = 255;
    }
    return image;
}

std::string writeImage(const std::filesystem::path& path, const image::ImageRgba8& image) {
    EXPECT_TRUE(image::writePng(path, image).ok());
    return path.string();
}

TEST(CompareCommandTest, PrintsSsimAndColourError) {
    const auto dir = makeTempDir("compare-values");
    const std::string a = writeImage(dir / "a.png", flat(24, 16, 100));
    const std::string b = writeImage(dir / "b.png", flat(24, 16, 150));

    const auto same = runEncore("compare " + quote(a) + " " + quote(a));
    ASSERT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.out.find("ssim: 1.000000"), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("max absolute error: 0"), std::string::npos) << same.out;

    // Flat images: SSIM is the luminance term (2ab + C1) / (a^2 + b^2 + C1) = 0.923463.
    const auto result = runEncore("compare " + quote(a) + " " + quote(b) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto report = nlohmann::json::parse(result.out);
    const double c1 = 2.55 * 2.55;
    EXPECT_NEAR(report["ssim"].get<double>(),
                (2 * 100.0 * 150 + c1) / (100.0 * 100 + 150 * 150 + c1), 1e-9);
    EXPECT_EQ(report["width"], 24);
    EXPECT_EQ(report["height"], 16);
    EXPECT_DOUBLE_EQ(report["colorError"]["meanAbsolute"].get<double>(), 50.0);
    EXPECT_EQ(report["colorError"]["maxAbsolute"], 50);
    EXPECT_DOUBLE_EQ(report["colorError"]["fractionOverThreshold"].get<double>(), 1.0);
}

TEST(CompareCommandTest, WritesFirstSecondAndDifferenceSideBySide) {
    const auto dir = makeTempDir("compare-side-by-side");
    const std::string a = writeImage(dir / "a.png", flat(20, 10, 100));
    const std::string b = writeImage(dir / "b.png", flat(20, 10, 110));
    const auto output = dir / "side.png";
    const auto result =
        runEncore("compare " + quote(a) + " " + quote(b) + " -o " + quote(output.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    auto side = image::readImage(output);
    ASSERT_TRUE(side.ok()) << side.error().message;
    EXPECT_EQ(side->width, 3u * 20 + 2 * 4);  // Three panels, two 4-pixel gaps.
    EXPECT_EQ(side->height, 10u);
    EXPECT_EQ(side->pixel(0, 0)[0], 100);
    EXPECT_EQ(side->pixel(24, 0)[0], 110);
    EXPECT_EQ(side->pixel(48, 0)[0], 40);  // |100 - 110| with gain 4.
}

TEST(CompareCommandTest, DifferentSizesAreAnError) {
    const auto dir = makeTempDir("compare-sizes");
    const std::string a = writeImage(dir / "a.png", flat(20, 10, 0));
    const std::string b = writeImage(dir / "b.png", flat(10, 20, 0));
    const auto output = dir / "side.png";
    const auto result =
        runEncore("compare " + quote(a) + " " + quote(b) + " -o " + quote(output.string()));
    EXPECT_EQ(result.exitCode, 1);
    EXPECT_EQ(result.err.rfind("error: " + b + ": ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find("(10x20)"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("(20x10)"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(output));
}

TEST(CompareCommandTest, UnreadableImagesAreAnError) {
    const auto dir = makeTempDir("compare-unreadable");
    const std::string a = writeImage(dir / "a.png", flat(4, 4, 0));
    const std::string missing = (dir / "missing.png").string();
    const auto absent = runEncore("compare " + quote(a) + " " + quote(missing));
    EXPECT_EQ(absent.exitCode, 1);
    EXPECT_EQ(absent.err.rfind("error: " + missing + ": ", 0), 0u) << absent.err;

    const std::string text = (dir / "text.png").string();
    std::ofstream(text) << "not an image";
    const auto garbage = runEncore("compare " + quote(text) + " " + quote(a));
    EXPECT_EQ(garbage.exitCode, 1);
    EXPECT_EQ(garbage.err.rfind("error: " + text + ": ", 0), 0u) << garbage.err;

    EXPECT_EQ(runEncore("compare " + quote(a)).exitCode, 2);  // Usage: B is missing.
}

}  // namespace
}  // namespace encore::test
