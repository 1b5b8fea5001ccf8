// `encore view` tested as a user meets it: under a virtual X display (Xvfb, through xvfb-run)
// on lavapipe, a scripted session renders, switches strategy and bundling, resizes, gets files
// dropped on it and takes screenshots, which must equal `encore render`'s pictures at the same
// camera and size, pixel for pixel; without a display it refuses and points to `encore render`.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "VariantFixture.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

// A 24-bit screen: xvfb-run's default is 8 bits deep, which Vulkan cannot present to.
const std::string kXvfb = "xvfb-run -a -s '-screen 0 1024x768x24 -nolisten tcp'";

bool haveXvfb() {
    return std::system("command -v xvfb-run >/dev/null 2>&1 && command -v Xvfb >/dev/null 2>&1") ==
           0;
}

std::vector<std::string> statsLines(const std::string& out) {
    std::vector<std::string> lines;
    std::istringstream text(out);
    std::string line;
    while (std::getline(text, line)) {
        if (line.starts_with("stats ")) {
            lines.push_back(line);
        }
    }
    return lines;
}

// The value of `key=` in a stats line (up to the next space; the error runs to the end).
std::string field(const std::string& line, const std::string& key) {
    const std::size_t start = line.find(" " + key + "=");
    if (start == std::string::npos) {
        return "";
    }
    const std::size_t begin = start + key.size() + 2;
    const std::size_t end = key == "error" ? line.size() : line.find(' ', begin);
    return line.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

image::ImageRgba8 readPng(const std::filesystem::path& path) {
    auto image = image::readImage(path);
    EXPECT_TRUE(image.ok()) << path << ": " << (image.ok() ? "" : image.error().message);
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

std::size_t differingPixels(const image::ImageRgba8& a, const image::ImageRgba8& b) {
    if (a.width != b.width || a.height != b.height) {
        return std::size_t(-1);
    }
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
        count += a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
                 a.pixels[i + 2] != b.pixels[i + 2];
    }
    return count;
}

// `encore render` of the same file at the same size and strategy (the default camera).
image::ImageRgba8 rendered(const std::filesystem::path& model,
                           const std::string& strategy,
                           std::uint32_t width,
                           std::uint32_t height,
                           const std::filesystem::path& out) {
    const auto result = runEncore("render " + quote(model.string()) + " --strategy " + strategy +
                                  " --width " + std::to_string(width) + " --height " +
                                  std::to_string(height) + " -o " + quote(out.string()));
    EXPECT_EQ(result.exitCode, 0) << result.err;
    return readPng(out);
}

TEST(ViewCommandTest, WithoutADisplayItRefusesAndPointsToRender) {
    const auto dir = makeTempDir("view-no-display");
    ASSERT_EQ(runEncore("gen --objects 4 -o " + quote((dir / "s.glb").string())).exitCode, 0);
    const auto result =
        runEncoreThrough("env -u DISPLAY", "view " + quote((dir / "s.glb").string()));
    EXPECT_EQ(result.exitCode, 6) << result.err;
    EXPECT_NE(result.err.find("error: No display"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("encore render"), std::string::npos) << result.err;
}

TEST(ViewCommandTest, AScriptedSessionShowsWhatRenderWrites) {
    if (!haveXvfb()) {
        GTEST_SKIP() << "xvfb-run (package xvfb) is not installed: no virtual display";
    }
    const auto dir = makeTempDir("view-session");
    const auto scene = dir / "scene.glb";
    const auto other = dir / "other.glb";
    const auto bad = dir / "bad.gltf";
    ASSERT_EQ(
        runEncore("gen --objects 40 --meshes 4 --materials 3 -o " + quote(scene.string())).exitCode,
        0);
    ASSERT_EQ(
        runEncore("gen --objects 12 --meshes 2 --materials 2 --seed 7 -o " + quote(other.string()))
            .exitCode,
        0);
    std::ofstream(bad) << R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 3}]})";
    const auto shot = [&](const std::string& name) { return (dir / name).string(); };
    std::ofstream(dir / "session.txt") << "frames 2\n"
                                       << "screenshot " << shot("bundles.png") << "\n"
                                       << "stats\n"
                                       << "key 1   # naive\n"
                                       << "frames 2\n"
                                       << "screenshot " << shot("naive.png") << "\n"
                                       << "key b   # naive recorded into a bundle\n"
                                       << "frames 2\n"
                                       << "stats\n"
                                       << "resize 200 120\n"
                                       << "frames 2\n"
                                       << "screenshot " << shot("resized.png") << "\n"
                                       << "stats\n"
                                       << "drop " << bad.string() << "\n"
                                       << "frames 1\n"
                                       << "stats\n"
                                       << "drop " << other.string() << "\n"
                                       << "frames 2\n"
                                       << "screenshot " << shot("dropped.png") << "\n"
                                       << "screenshot " << shot("overlay.png") << " overlay\n"
                                       << "stats\n";
    const auto result = runEncoreThrough(kXvfb, "view " + quote(scene.string()) +
                                                    " --width 160 --height 120 --script " +
                                                    quote((dir / "session.txt").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
    const auto stats = statsLines(result.out);
    ASSERT_EQ(stats.size(), 5u) << result.out;

    EXPECT_EQ(field(stats[0], "strategy"), "bundles");
    EXPECT_EQ(field(stats[0], "bundlesRecorded"), "1");
    EXPECT_EQ(field(stats[0], "executeBundles"), "1");
    EXPECT_EQ(differingPixels(readPng(shot("bundles.png")),
                              rendered(scene, "bundles", 160, 120, dir / "r-bundles.png")),
              0u);
    EXPECT_EQ(differingPixels(readPng(shot("naive.png")),
                              rendered(scene, "naive", 160, 120, dir / "r-naive.png")),
              0u);

    // B: naive recorded once into a bundle; the resize records nothing again.
    EXPECT_EQ(field(stats[1], "strategy"), "naive+bundle");
    EXPECT_EQ(field(stats[1], "bundlesRecorded"), "1");
    EXPECT_EQ(field(stats[1], "draws"), "0");
    EXPECT_EQ(field(stats[2], "size"), "200x120");
    EXPECT_EQ(field(stats[2], "bundlesRecorded"), "1");
    EXPECT_EQ(differingPixels(readPng(shot("resized.png")),
                              rendered(scene, "naive", 200, 120, dir / "r-resized.png")),
              0u);

    // A bad file shows its error and keeps the scene; a good one replaces it.
    EXPECT_NE(field(stats[3], "error").find("bad.gltf"), std::string::npos) << stats[3];
    EXPECT_EQ(field(stats[3], "scene"), scene.string());
    EXPECT_EQ(field(stats[4], "scene"), other.string());
    EXPECT_EQ(field(stats[4], "bundlesRecorded"), "1");
    const image::ImageRgba8 dropped = readPng(shot("dropped.png"));
    EXPECT_EQ(differingPixels(dropped, rendered(other, "naive", 200, 120, dir / "r-other.png")),
              0u);
    // The overlay is drawn over the same frame only when asked for.
    EXPECT_GT(differingPixels(readPng(shot("overlay.png")), dropped), 2000u);
}

// Keys 1-8 and B switch the strategy only: the GPU scene (geometry, textures) is uploaded
// once, whichever strategies draw it; a dropped file is the next upload.
TEST(ViewCommandTest, SwitchingStrategiesUploadsTheSceneOnce) {
    if (!haveXvfb()) {
        GTEST_SKIP() << "xvfb-run (package xvfb) is not installed: no virtual display";
    }
    const auto dir = makeTempDir("view-switch");
    const auto scene = dir / "scene.glb";
    const auto other = dir / "other.glb";
    ASSERT_EQ(
        runEncore("gen --objects 20 --meshes 3 --materials 3 -o " + quote(scene.string())).exitCode,
        0);
    ASSERT_EQ(
        runEncore("gen --objects 6 --meshes 2 --materials 2 --seed 5 -o " + quote(other.string()))
            .exitCode,
        0);
    std::ofstream script(dir / "session.txt");
    script << "frames 1\nstats\n";
    for (char key = '1'; key <= '8'; ++key) {
        script << "key " << key << "\nframes 1\nstats\nkey b\nframes 1\nstats\n";
    }
    script << "drop " << other.string() << "\nframes 1\nstats\n";
    script.close();
    const auto result = runEncoreThrough(kXvfb, "view " + quote(scene.string()) +
                                                    " --width 96 --height 64 --script " +
                                                    quote((dir / "session.txt").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
    const auto stats = statsLines(result.out);
    ASSERT_EQ(stats.size(), 18u) << result.out;
    const std::string uploaded = field(stats[0], "uploadedBytes");
    EXPECT_GT(std::stoull(uploaded), 0u) << stats[0];
    std::set<std::string> strategies;
    for (std::size_t i = 0; i + 1 < stats.size(); ++i) {
        SCOPED_TRACE(stats[i]);
        EXPECT_EQ(field(stats[i], "error"), "");
        EXPECT_EQ(field(stats[i], "sceneUploads"), "1");
        EXPECT_EQ(field(stats[i], "uploadedBytes"), uploaded);
        strategies.insert(field(stats[i], "strategy") + field(stats[i], "bundled"));
    }
    // Every strategy, directly and from a bundle (bundles and gpu-culling-bundles are the
    // bundled forms of materials and gpu-culling).
    EXPECT_GE(strategies.size(), 12u);
    EXPECT_EQ(field(stats.back(), "scene"), other.string());
    EXPECT_EQ(field(stats.back(), "sceneUploads"), "2");
    EXPECT_GT(std::stoull(field(stats.back(), "uploadedBytes")), std::stoull(uploaded));
}

// V cycles the material variants (KHR_materials_variants): each frame is the picture `encore
// render --variant` writes, bundles record again, and nothing is uploaded again.
TEST(ViewCommandTest, VCyclesTheMaterialVariantsWithoutUploading) {
    if (!haveXvfb()) {
        GTEST_SKIP() << "xvfb-run (package xvfb) is not installed: no virtual display";
    }
    const auto dir = makeTempDir("view-variants");
    const auto model = variantQuads().writeGlb(dir, "quads");
    std::ofstream script(dir / "session.txt");
    script << "frames 1\nstats\n";
    for (int i = 0; i < 5; ++i) {  // Every variant, then the default again.
        script << "key v\nframes 1\nscreenshot "
               << (dir / ("v" + std::to_string(i) + ".png")).string() << "\nstats\n";
    }
    script.close();
    const auto result = runEncoreThrough(kXvfb, "view " + quote(model.string()) +
                                                    " --width 96 --height 64 --variant green"
                                                    " --script " +
                                                    quote((dir / "session.txt").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
    const auto stats = statsLines(result.out);
    ASSERT_EQ(stats.size(), 6u) << result.out;
    // --variant green first, then blue paint, glass, textured, the default, green.
    const std::vector<std::string> expected = {"0", "1", "2", "3", "default", "0"};
    const std::string uploaded = field(stats[0], "uploadedBytes");
    for (std::size_t i = 0; i < stats.size(); ++i) {
        SCOPED_TRACE(stats[i]);
        EXPECT_EQ(field(stats[i], "variant"), expected[i]);
        EXPECT_EQ(field(stats[i], "sceneUploads"), "1");
        EXPECT_EQ(field(stats[i], "uploadedBytes"), uploaded);
        EXPECT_EQ(field(stats[i], "error"), "");
        // Every switch records again (the blended variant a second bundle for its draw).
        if (i > 0) {
            EXPECT_GT(std::stoull(field(stats[i], "bundlesRecorded")),
                      std::stoull(field(stats[i - 1], "bundlesRecorded")));
        }
    }
    for (int i = 0; i < 5; ++i) {
        const std::string variant = expected[std::size_t(i + 1)];
        const auto out = dir / ("r" + std::to_string(i) + ".png");
        const auto render =
            runEncore("render " + quote(model.string()) + " --width 96 --height 64 -o " +
                      quote(out.string()) + (variant == "default" ? "" : " --variant " + variant));
        ASSERT_EQ(render.exitCode, 0) << render.err;
        EXPECT_EQ(differingPixels(readPng(dir / ("v" + std::to_string(i) + ".png")), readPng(out)),
                  0u)
            << "variant " << variant;
    }
}

// A variant the file lacks is refused before any window opens.
TEST(ViewCommandTest, AVariantTheFileLacksIsAUsageError) {
    const auto dir = makeTempDir("view-bad-variant");
    const auto model = variantQuads().writeGlb(dir, "quads");
    const auto result =
        runEncoreThrough("env -u DISPLAY", "view " + quote(model.string()) + " --variant chrome");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("has no material variant 'chrome' (its variants: 0 'green'"),
              std::string::npos)
        << result.err;
}

TEST(ViewCommandTest, TheAnimometerRunsDirectAndBundled) {
    if (!haveXvfb()) {
        GTEST_SKIP() << "xvfb-run (package xvfb) is not installed: no virtual display";
    }
    const auto dir = makeTempDir("view-animometer");
    std::ofstream(dir / "session.txt") << "frames 2\nstats\nkey b\nresize 96 64\nframes 2\nstats\n"
                                       << "screenshot " << (dir / "a.png").string() << "\n";
    const auto result =
        runEncoreThrough(kXvfb, "view --animometer 500 --width 128 --height 96 --script " +
                                    quote((dir / "session.txt").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
    const auto stats = statsLines(result.out);
    ASSERT_EQ(stats.size(), 2u) << result.out;
    EXPECT_EQ(field(stats[0], "draws"), "500");
    EXPECT_EQ(field(stats[0], "executeBundles"), "0");
    EXPECT_EQ(field(stats[1], "draws"), "0");
    EXPECT_EQ(field(stats[1], "executeBundles"), "1");
    EXPECT_EQ(field(stats[1], "size"), "96x64");
    const image::ImageRgba8 image = readPng(dir / "a.png");
    EXPECT_EQ(image.width, 96u);
    EXPECT_EQ(image.height, 64u);
}

TEST(ViewCommandTest, ABadScriptIsAUsageErrorNamingTheLine) {
    const auto dir = makeTempDir("view-bad-script");
    std::ofstream(dir / "session.txt") << "frames 2\nkey nope\n";
    const auto result = runEncoreThrough(
        "env -u DISPLAY", "view --animometer 10 --script " + quote((dir / "session.txt").string()));
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("session.txt:2: unknown key 'nope'"), std::string::npos)
        << result.err;
}

}  // namespace
}  // namespace encore::test
