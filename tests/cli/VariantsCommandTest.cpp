// KHR_materials_variants from the command line: `encore render --variant` draws a variant by
// name or index, a variant the file lacks is a usage error naming the file and its variants,
// and `encore batch --variants all` writes each variant as a sample of its own
// (OUT/<name>@<variant>), resuming sample by sample; `--variant` writes one.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "VariantFixture.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

// A camera on +Z looking at the quads: the left one's centre is pixel (20, 32) of 64x64.
const std::string kCamera =
    " --camera-position=0,0,3 --target=0,0,0 --yfov 90 --width 64 --height 64";

image::ImageRgba8 readPng(const fs::path& path) {
    auto image = image::readImage(path);
    EXPECT_TRUE(image.ok()) << path;
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// The channel (0 red, 1 green, 2 blue) that dominates a pixel.
int dominantChannel(const image::ImageRgba8& image, std::uint32_t x, std::uint32_t y) {
    const std::uint8_t* pixel = image.pixel(x, y);
    return pixel[1] > pixel[0] && pixel[1] > pixel[2] ? 1 : pixel[2] > pixel[0] ? 2 : 0;
}

bool sameImages(const fs::path& a, const fs::path& b) {
    return readPng(a).pixels == readPng(b).pixels;
}

std::string slurp(const fs::path& path) {
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

TEST(VariantsCommandTest, RenderDrawsAVariantByNameOrIndex) {
    const fs::path dir = makeTempDir("render-variants");
    const fs::path model = variantQuads().writeGlb(dir, "quads");
    const auto render = [&](const std::string& variant, const std::string& name) {
        const fs::path out = dir / (name + ".png");
        const CommandResult result = runEncore("render " + quote(model.string()) + kCamera +
                                               variant + " -o " + quote(out.string()));
        EXPECT_EQ(result.exitCode, 0) << result.err;
        return out;
    };
    const fs::path plain = render("", "default");
    const fs::path green = render(" --variant green", "green");
    const fs::path blue = render(" --variant 'blue paint'", "blue");
    const fs::path byIndex = render(" --variant 1", "index");
    EXPECT_EQ(dominantChannel(readPng(plain), 20, 32), 0);
    EXPECT_EQ(dominantChannel(readPng(green), 20, 32), 1);
    EXPECT_EQ(dominantChannel(readPng(blue), 20, 32), 2);
    EXPECT_TRUE(sameImages(blue, byIndex));
    // The right quad is mapped by no variant.
    EXPECT_EQ(readPng(plain).pixel(44, 32)[0], readPng(green).pixel(44, 32)[0]);
}

TEST(VariantsCommandTest, AVariantTheFileLacksIsAUsageError) {
    const fs::path dir = makeTempDir("render-bad-variant");
    const fs::path model = variantQuads().writeGlb(dir, "quads");
    const CommandResult result = runEncore("render " + quote(model.string()) +
                                           " --variant red -o " + quote((dir / "x.png").string()));
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.err, "error: '" + model.string() +
                              "' has no material variant 'red' (its variants: 0 'green', 1 'blue "
                              "paint', 2 'glass', 3 'textured'; give a name or an index).\n");
    EXPECT_FALSE(fs::exists(dir / "x.png"));

    ASSERT_EQ(runEncore("gen --objects 2 -o " + quote((dir / "plain.glb").string())).exitCode, 0);
    const CommandResult none = runEncore("render " + quote((dir / "plain.glb").string()) +
                                         " --variant 0 -o " + quote((dir / "y.png").string()));
    EXPECT_EQ(none.exitCode, 2);
    EXPECT_NE(none.err.find("it uses no KHR_materials_variants"), std::string::npos) << none.err;
}

TEST(VariantsCommandTest, BatchWritesEveryVariantAsASampleAndResumes) {
    const fs::path dir = makeTempDir("batch-variants");
    const fs::path model = variantQuads().writeGlb(dir, "quads");
    const fs::path out = dir / "out";
    const std::string arguments = "batch " + quote(model.string()) + " -o " + quote(out.string()) +
                                  " --views 2 --size 48 --renderers 1 --quiet --variants all";
    const CommandResult run = runEncore(arguments);
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("1 rendered, 0 failed, 0 skipped of 1 models; 10 views"),
              std::string::npos)
        << run.out;
    const std::vector<std::string> samples = {"quads", "quads@green", "quads@blue_paint",
                                              "quads@glass", "quads@textured"};
    for (const std::string& sample : samples) {
        SCOPED_TRACE(sample);
        for (const char* file : {"000.png", "001.png", "transforms.json"}) {
            EXPECT_TRUE(fs::is_regular_file(out / sample / file)) << file;
        }
    }
    // Each sample has its own look; the views of one variant are the default's elsewhere.
    for (std::size_t i = 1; i < samples.size(); ++i) {
        EXPECT_FALSE(sameImages(out / samples[0] / "000.png", out / samples[i] / "000.png"))
            << samples[i];
    }
    EXPECT_EQ(slurp(out / "quads" / "transforms.json"),
              slurp(out / "quads@glass" / "transforms.json"));

    // Finished: nothing is drawn again.
    const auto written = fs::last_write_time(out / "quads@green" / "000.png");
    const CommandResult again = runEncore(arguments);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find("0 rendered, 0 failed, 1 skipped of 1 models"), std::string::npos)
        << again.out;
    // One sample lost: only it is drawn again.
    fs::remove(out / "quads@glass" / "transforms.json");
    const std::string glass = slurp(out / "quads@glass" / "000.png");
    fs::remove(out / "quads@glass" / "000.png");
    const CommandResult resumed = runEncore(arguments);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
    EXPECT_NE(resumed.out.find("1 rendered, 0 failed, 0 skipped of 1 models; 2 views"),
              std::string::npos)
        << resumed.out;
    EXPECT_EQ(fs::last_write_time(out / "quads@green" / "000.png"), written);
    EXPECT_EQ(slurp(out / "quads@glass" / "000.png"), glass);
    EXPECT_TRUE(fs::is_regular_file(out / "quads@glass" / "transforms.json"));
}

TEST(VariantsCommandTest, BatchWritesOneVariantAndListsModelsWithoutIt) {
    const fs::path dir = makeTempDir("batch-one-variant");
    const fs::path models = dir / "models";
    fs::create_directories(models);
    variantQuads().writeGlb(models, "quads");
    ASSERT_EQ(runEncore("gen --objects 2 -o " + quote((models / "plain.glb").string())).exitCode,
              0);
    const fs::path out = dir / "out";
    const CommandResult run =
        runEncore("batch " + quote(models.string()) + " -o " + quote(out.string()) +
                  " --views 1 --size 32 --quiet --variant 'blue paint'");
    EXPECT_EQ(run.exitCode, 1) << run.out << run.err;
    EXPECT_TRUE(fs::is_regular_file(out / "quads@blue_paint" / "transforms.json"));
    EXPECT_FALSE(fs::exists(out / "quads"));
    const std::string failures = slurp(out / "failures.jsonl");
    EXPECT_NE(failures.find("plain.glb"), std::string::npos) << failures;
    EXPECT_NE(failures.find("\"stage\":\"load\""), std::string::npos) << failures;
    EXPECT_NE(failures.find("has no material variant 'blue paint'"), std::string::npos) << failures;

    const CommandResult both = runEncore("batch " + quote(models.string()) + " -o " +
                                         quote(out.string()) + " --variant 0 --variants all");
    EXPECT_EQ(both.exitCode, 2) << both.err;
}

}  // namespace
}  // namespace encore::test
