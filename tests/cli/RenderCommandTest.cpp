// `encore render` from the command line, as a user reproduces a picture: the reference's exact
// camera, environment and background given as options give the reference comparison's result,
// and the shading options reach the image (transparent background, debug channels, errors).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"
#include "image/ImageCompare.h"

namespace encore::test {
namespace {

std::string vectorOption(const nlohmann::json& v) {
    std::ostringstream text;
    text << v[0].get<double>() << "," << v[1].get<double>() << "," << v[2].get<double>();
    return text.str();
}

TEST(RenderCommandTest, ReproducesTheReferencePictureFromTheCommandLine) {
    const auto reference = sharedReferenceDir();
    const auto models = sharedModelsDir();
    if (!reference || !models) {
        GTEST_SKIP() << "../shared/reference or ../shared/models is absent beside the clone";
    }
    std::ifstream jsonFile(*reference / "Duck.json");
    const auto description = nlohmann::json::parse(jsonFile);
    const auto& camera = description["camera"];
    const auto out = makeTempDir("render-reference") / "duck.png";
    const auto result = runEncore(
        "render " + quote((*models / "Duck/glTF/Duck.gltf").string()) +
        " --width 320 --height 320 --environment " + quote((*reference / "studio.hdr").string()) +
        " --environment-rotation 90 --background '#000000' --camera-position=" +
        vectorOption(camera["position"]) + " --target=" + vectorOption(camera["target"]) +
        " --yfov " + std::to_string(camera["yfovDegrees"].get<double>()) + " --znear " +
        std::to_string(camera["znear"].get<double>()) + " --zfar " +
        std::to_string(camera["zfar"].get<double>()) + " -o " + quote(out.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    auto encore = image::readImage(out);
    auto expected = image::readImage(*reference / "Duck.png");
    ASSERT_TRUE(encore.ok() && expected.ok());
    auto ssim = image::ssimLuminance(*encore, *expected);
    ASSERT_TRUE(ssim.ok());
    EXPECT_GE(*ssim, 0.98);
}

// A valid scene that draws nothing: every strategy writes the background alone, prints a
// warning and exits with 0.
TEST(RenderCommandTest, EmptySceneRendersTheBackgroundWithAWarning) {
    const auto dir = makeTempDir("render-empty");
    const auto scene = dir / "empty.gltf";
    std::ofstream(scene) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
                               "nodes": [{"name": "no mesh"}], "scene": 0})";
    for (const char* strategy : {"naive", "layouts", "pipeline-cache", "instancing", "materials",
                                 "bundles", "gpu-culling", "gpu-culling-bundles"}) {
        const auto out = dir / (std::string(strategy) + ".png");
        const auto result =
            runEncore("render " + quote(scene.string()) + " --width 48 --height 32 --strategy " +
                      strategy + " -o " + quote(out.string()));
        ASSERT_EQ(result.exitCode, 0) << strategy << ": " << result.err;
        EXPECT_NE(result.err.find("warning: " + scene.string() + ": The asset draws nothing"),
                  std::string::npos)
            << strategy << ": " << result.err;
        auto image = image::readImage(out);
        ASSERT_TRUE(image.ok()) << strategy << ": " << image.error().message;
        ASSERT_EQ(image->width, 48u);
        ASSERT_EQ(image->height, 32u);
        for (std::size_t i = 4; i < image->pixels.size(); ++i) {
            ASSERT_EQ(image->pixels[i], image->pixels[i % 4])
                << strategy << ": byte " << i << " differs from the background";
        }
    }
}

// A generated scene, framed automatically, with a transparent background: the corners are
// transparent, the objects opaque.
TEST(RenderCommandTest, TransparentBackgroundLeavesAlphaZeroAroundTheScene) {
    const auto dir = makeTempDir("render-transparent");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(
        runEncore("gen --objects 20 --meshes 2 --materials 2 -o " + quote(scene.string())).exitCode,
        0);
    const auto png = dir / "out.png";
    const auto result =
        runEncore("render " + quote(scene.string()) +
                  " --width 96 --height 64 --background transparent -o " + quote(png.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    auto image = image::readImage(png);
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->pixel(0, 0)[3], 0);
    std::size_t opaque = 0;
    for (std::size_t i = 3; i < image->pixels.size(); i += 4) {
        opaque += image->pixels[i] == 255;
    }
    EXPECT_GT(opaque, 200u);
}

TEST(RenderCommandTest, BadShadingOptionsAreUsageErrors) {
    const auto dir = makeTempDir("render-options");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(runEncore("gen --objects 2 -o " + quote(scene.string())).exitCode, 0);
    const auto background =
        runEncore("render " + quote(scene.string()) + " --background '#12345' -o " +
                  quote((dir / "a.png").string()));
    EXPECT_EQ(background.exitCode, 2);
    EXPECT_NE(background.err.find("#12345"), std::string::npos) << background.err;
    const auto channel = runEncore("render " + quote(scene.string()) +
                                   " --debug-channel albedo -o " + quote((dir / "b.png").string()));
    EXPECT_EQ(channel.exitCode, 2);
    EXPECT_NE(channel.err.find("albedo"), std::string::npos) << channel.err;
    const auto environment =
        runEncore("render " + quote(scene.string()) + " --environment " +
                  quote((dir / "none.hdr").string()) + " -o " + quote((dir / "c.png").string()));
    EXPECT_EQ(environment.exitCode, 1);
    EXPECT_NE(environment.err.find("none.hdr"), std::string::npos) << environment.err;
}

// --frames renders an image sequence from one prepared renderer, one file per time; an animated
// model's frames differ.
TEST(RenderCommandTest, FramesWriteAnImageSequence) {
    const auto dir = makeTempDir("render-frames");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(runEncore("gen --objects 2 -o " + quote(scene.string())).exitCode, 0);
    const auto result = runEncore("render " + quote(scene.string()) +
                                  " --width 32 --height 32 --samples 1 --frames 0:0.2:0.1 -o " +
                                  quote((dir / "frame_%02d.png").string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    for (const char* name : {"frame_00.png", "frame_01.png", "frame_02.png"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "frame_03.png"));

    const auto models = sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "The shared models directory is absent.";
    }
    const auto cube = *models / "AnimatedMorphCube" / "glTF-Binary" / "AnimatedMorphCube.glb";
    if (!std::filesystem::exists(cube)) {
        GTEST_SKIP() << cube << " is absent.";
    }
    const auto animated = runEncore("render " + quote(cube.string()) +
                                    " --width 48 --height 48 --samples 1 --animation 0"
                                    " --frames 0:1.5:1.5 -o " +
                                    quote((dir / "cube_%d.png").string()));
    ASSERT_EQ(animated.exitCode, 0) << animated.err;
    auto first = image::readImage(dir / "cube_0.png");
    auto second = image::readImage(dir / "cube_1.png");
    ASSERT_TRUE(first.ok() && second.ok());
    EXPECT_NE(first->pixels, second->pixels);
}

TEST(RenderCommandTest, BadAnimationOptionsAreUsageErrors) {
    const auto dir = makeTempDir("render-animation-options");
    const auto scene = dir / "scene.glb";
    ASSERT_EQ(runEncore("gen --objects 2 -o " + quote(scene.string())).exitCode, 0);
    const std::string render = "render " + quote(scene.string()) + " --width 16 --height 16 ";
    const std::string pattern = " -o " + quote((dir / "f_%03d.png").string());
    for (const std::string& options :
         {std::string("--frames 1:0:1") + pattern, std::string("--frames 0:1:0") + pattern,
          std::string("--frames 0:1") + pattern, std::string("--frames a:b:c") + pattern,
          std::string("--frames 0:1:0.5 --time 1") + pattern,
          "--frames 0:1:0.5 -o " + quote((dir / "no-pattern.png").string()),
          "--time nan -o " + quote((dir / "t.png").string()),
          "--time 1 --animation Walk -o " + quote((dir / "t.png").string()),
          "--time 1 --animate gpus -o " + quote((dir / "t.png").string())}) {
        const auto result = runEncore(render + options);
        EXPECT_EQ(result.exitCode, 2) << options << "\n" << result.err;
        EXPECT_FALSE(result.err.empty()) << options;
    }
}

// --animate gpu draws the frame --animate cpu draws, and `encore stats` reports the GPU work.
TEST(RenderCommandTest, GpuAnimationRendersTheCpuFrame) {
    const auto models = sharedModelsDir();
    if (!models) {
        GTEST_SKIP() << "The shared models directory is absent.";
    }
    const auto fox = *models / "Fox" / "glTF-Binary" / "Fox.glb";
    if (!std::filesystem::exists(fox)) {
        GTEST_SKIP() << fox << " is absent.";
    }
    const auto dir = makeTempDir("render-animate");
    for (const char* evaluation : {"cpu", "gpu"}) {
        const auto result =
            runEncore("render " + quote(fox.string()) +
                      " --width 48 --height 48 --samples 1 --time 0.7 --animate " + evaluation +
                      " -o " + quote((dir / (std::string(evaluation) + ".png")).string()));
        ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    auto cpu = image::readImage(dir / "cpu.png");
    auto gpu = image::readImage(dir / "gpu.png");
    ASSERT_TRUE(cpu.ok() && gpu.ok());
    EXPECT_EQ(cpu->pixels, gpu->pixels);

    const auto stats = runEncore("stats " + quote(fox.string()) +
                                 " --strategy bundles --time 0.7 --animate gpu --json");
    ASSERT_EQ(stats.exitCode, 0) << stats.err;
    const auto report = nlohmann::json::parse(stats.out);
    const auto& animation = report["strategies"][0]["animation"];
    EXPECT_EQ(animation["evaluation"], "gpu");
    EXPECT_GT(animation["computeDispatches"].get<int>(), 2);
    EXPECT_EQ(animation["bytesWritten"].get<int>(), 12);  // The times of Fox's 3 animations.
}

}  // namespace
}  // namespace encore::test
