// `encore bench --smoke` in CI: the benchmark path cannot rot. Checks the report, not speed.

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

TEST(BenchSmokeTest, WritesACompleteReportOnVulkan) {
    const auto dir = makeTempDir("bench-smoke");
    const auto json = dir / "report.json";
    const auto markdown = dir / "report.md";
    const auto result = runEncore("bench --smoke --json " + quote(json.string()) + " --markdown " +
                                  quote(markdown.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    std::ifstream file(json);
    const auto report = nlohmann::json::parse(file, nullptr, false);
    ASSERT_FALSE(report.is_discarded());
    // Numbers from Dawn's Null backend would be meaningless.
    EXPECT_EQ(report["adapter"]["backend"], "Vulkan");
    EXPECT_FALSE(report["adapter"]["name"].get<std::string>().empty());
    EXPECT_NE(report["dawn"], "unknown");
    EXPECT_EQ(report["gpuWait"], "spin");
    EXPECT_EQ(report["generated"]["textures"], true);
    const auto& results = report["results"];
    ASSERT_EQ(results.size(), 2u * 9u);  // Two scenes, every strategy.
    for (const auto& entry : results) {
        SCOPED_TRACE(entry["label"].get<std::string>() + " / " +
                     entry["strategy"].get<std::string>());
        EXPECT_GT(entry["cpuMs"]["median"].get<double>(), 0.0);
        EXPECT_GE(entry["cpuMs"]["p95"].get<double>(), entry["cpuMs"]["median"].get<double>());
        if (report["timestamps"].get<bool>()) {
            EXPECT_GT(entry["gpuMs"]["median"].get<double>(), 0.0);
        }
        const std::uint64_t draws = entry["frame"]["draw"].get<std::uint64_t>() +
                                    entry["frame"]["drawIndexed"].get<std::uint64_t>() +
                                    entry["frame"]["drawIndirect"].get<std::uint64_t>() +
                                    entry["bundleContents"]["drawIndexed"].get<std::uint64_t>() +
                                    entry["bundleContents"]["drawIndirect"].get<std::uint64_t>();
        // The visibility strategy composes its frames in compute (no draw at all with a plain
        // background): its triangles are rasterised in compute.
        std::uint64_t computeTriangles = 0;
        if (entry.contains("trianglesCompute")) {
            for (const auto& frame : entry["trianglesCompute"]) {
                computeTriangles += frame.get<std::uint64_t>();
            }
        }
        EXPECT_GT(draws + computeTriangles, 0u);
        if (entry["strategy"] == "visibility") {
            EXPECT_GT(computeTriangles, 0u);
        }
    }
    EXPECT_EQ(results[0]["strategy"], "naive");
    EXPECT_EQ(results[0]["frame"]["drawIndexed"], 100);  // One draw per object.
    std::ifstream text(markdown);
    const std::string table((std::istreambuf_iterator<char>(text)), {});
    EXPECT_NE(table.find("| gpu-culling-bundles |"), std::string::npos);
    EXPECT_NE(table.find("Vulkan"), std::string::npos);
}

// `encore gen --crowd` writes an animated crowd, and `encore bench --crowd` measures it with the
// animation evaluated on the CPU and on the GPU.
TEST(BenchSmokeTest, MeasuresAnAnimatedCrowdOnTheCpuAndTheGpu) {
    const auto dir = makeTempDir("bench-crowd");
    const auto crowd = dir / "crowd.glb";
    const auto generated = runEncore("gen --crowd 12 -o " + quote(crowd.string()));
    ASSERT_EQ(generated.exitCode, 0) << generated.err;
    const auto rendered = runEncore("render " + quote(crowd.string()) +
                                    " --width 32 --height 32 --samples 1 --time 0.5 --animate gpu"
                                    " -o " +
                                    quote((dir / "crowd.png").string()));
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;

    const auto run =
        runBench(dir, "--crowd 9 -s naive -s bundles --frames 2 --warmup 1 --width 32 --height 32");
    ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
    ASSERT_FALSE(run.report.is_discarded());
    const auto& report = run.report;
    const auto& results = report["results"];
    ASSERT_EQ(results.size(), 4u);  // cpu and gpu evaluation, two strategies each.
    EXPECT_EQ(results[0]["animation"], "cpu");
    EXPECT_EQ(results[3]["animation"], "gpu");
    for (const auto& entry : results) {
        EXPECT_EQ(entry["scene"], "crowd");
        EXPECT_EQ(entry["objects"], 9);
        EXPECT_GT(entry["cpuMs"]["median"].get<double>(), 0.0);
        // The evaluation's own time is part of the CPU frame, and its work is reported.
        EXPECT_GT(entry["animationMs"]["median"].get<double>(), 0.0);
        EXPECT_LE(entry["animationMs"]["median"].get<double>(),
                  entry["encodeMs"]["median"].get<double>());
        const auto& work = entry["animationWork"];
        if (entry["animation"] == "cpu") {
            EXPECT_GT(work["channelsEvaluated"].get<int>(), 0);
            EXPECT_GT(work["jointsWritten"].get<int>(), 0);
            EXPECT_EQ(work["gpuDispatches"], 0);
        } else {
            EXPECT_EQ(work["channelsEvaluated"], 0);
            EXPECT_GT(work["gpuDispatches"].get<int>(), 0);
        }
        EXPECT_GT(work["bytesWritten"].get<int>(), 0);
    }
}

// `encore bench --scene flythrough,city`: the camera follows each scene's path, and every
// measured frame reports the triangles its draws could draw and, with GPU culling, those drawn.
TEST(BenchSmokeTest, FlythroughAndCityReportTrianglesPerFrame) {
    const auto dir = makeTempDir("bench-scenes");
    const auto run = runBench(dir,
                              "--scene flythrough,city --objects 200 --frames 3 --warmup 1 "
                              "-s bundles -s gpu-culling-bundles -s visibility --width 64 "
                              "--height 64");
    ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
    ASSERT_FALSE(run.report.is_discarded());
    EXPECT_EQ(run.report["generated"]["scenes"], nlohmann::json({"flythrough", "city"}));
    const auto& results = run.report["results"];
    ASSERT_EQ(results.size(), 6u);  // Two scenes, three strategies.
    EXPECT_EQ(results[0]["scene"], "flythrough");
    EXPECT_EQ(results[0]["label"], "flythrough 200 objects");
    EXPECT_EQ(results[3]["scene"], "city");
    for (const auto& entry : results) {
        SCOPED_TRACE(entry["label"].get<std::string>() + " / " +
                     entry["strategy"].get<std::string>());
        EXPECT_EQ(entry["objects"], 200);
        const auto& submitted = entry["trianglesSubmitted"];
        ASSERT_EQ(submitted.size(), 3u);
        for (const auto& count : submitted) {
            EXPECT_GT(count.get<std::uint64_t>(), 0u);
            EXPECT_EQ(count, submitted[0]);  // Every object, every frame.
        }
        if (entry["strategy"] == "bundles") {
            EXPECT_TRUE(entry["trianglesDrawn"].is_null());
            continue;
        }
        const auto& drawn = entry["trianglesDrawn"];
        ASSERT_EQ(drawn.size(), 3u);
        for (const auto& count : drawn) {
            EXPECT_GT(count.get<std::uint64_t>(), 0u);
            EXPECT_LT(count.get<std::uint64_t>(), submitted[0].get<std::uint64_t>())
                << "the camera inside the scene sees part of it";
        }
        // Only the visibility buffer rasterises in compute: part of what it draws.
        const auto& compute = entry["trianglesCompute"];
        if (entry["strategy"] != "visibility") {
            EXPECT_TRUE(compute.is_null());
            continue;
        }
        ASSERT_EQ(compute.size(), 3u);
        for (std::size_t frame = 0; frame < 3; ++frame) {
            EXPECT_GT(compute[frame].get<std::uint64_t>(), 0u);
            EXPECT_LE(compute[frame].get<std::uint64_t>(), drawn[frame].get<std::uint64_t>());
        }
    }
    EXPECT_NE(
        run.command.out.find("| triangles submitted | triangles drawn | of them in compute |"),
        std::string::npos)
        << run.command.out;
}

// Under the GPU timer the visibility strategy's phases are timed as the frame runs them, one
// pass each; --gpu-steps times each step (culling, rasters, pyramid, binning, shading) apart;
// "gpuSpanMs" is the frame's span, passes and transfers. The
// city's four materials share one shading bin, which is not binned; seventy meshes of as many
// untextured materials fill two bins (MaterialBins::kBinMaterials each), whose tiles are.
TEST(BenchSmokeTest, VisibilityPassesAsTheyRunOrStepByStep) {
    const auto dir = makeTempDir("bench-steps");
    const std::string args =
        "--scene city --objects 200 --frames 2 --warmup 1 -s visibility --width 64 --height 64";
    const auto phases = runBench(dir, args);
    ASSERT_EQ(phases.command.exitCode, 0) << phases.command.err;
    if (phases.report["timestamps"] != true) {
        GTEST_SKIP() << "The adapter has no timestamp queries.";
    }
    const auto steps = runBench(dir, args + " --gpu-steps");
    ASSERT_EQ(steps.command.exitCode, 0) << steps.command.err;
    EXPECT_EQ(phases.report["gpuSteps"], false);
    EXPECT_EQ(steps.report["gpuSteps"], true);
    // The frame's span (first pass to the frame's end) holds its passes and what lies between.
    const auto& result = phases.report["results"][0];
    ASSERT_TRUE(result["gpuSpanMs"].is_object()) << result.dump();
    EXPECT_GE(result["gpuSpanMs"]["median"].get<double>(), result["gpuMs"]["median"].get<double>());
    const auto& asRun = phases.report["results"][0]["gpuPassesMs"];
    const auto& apart = steps.report["results"][0]["gpuPassesMs"];
    for (const char* phase : {"visibility: culling and compute raster",
                              "visibility: depth pyramid, second culling and raster",
                              "visibility: binning and shading"}) {
        EXPECT_TRUE(asRun.contains(phase)) << phase << " in " << asRun.dump();
        EXPECT_FALSE(apart.contains(phase)) << phase << " in " << apart.dump();
    }
    for (const char* step : {"visibility compute raster", "visibility workgroup raster",
                             "visibility depth pyramid", "visibility occlusion culling",
                             "visibility compute raster (second phase)", "visibility shading"}) {
        EXPECT_TRUE(apart.contains(step)) << step << " in " << apart.dump();
        EXPECT_FALSE(asRun.contains(step)) << step << " in " << asRun.dump();
    }
    EXPECT_LT(asRun.size(), apart.size());
    EXPECT_FALSE(apart.contains("visibility binning")) << apart.dump();

    const auto twoBins =
        runBench(dir, args + " --gpu-steps --meshes 70 --materials 70 --no-textures");
    ASSERT_EQ(twoBins.command.exitCode, 0) << twoBins.command.err;
    const auto& binned = twoBins.report["results"][0]["gpuPassesMs"];
    EXPECT_TRUE(binned.contains("visibility binning")) << binned.dump();
    EXPECT_TRUE(binned.contains("visibility shading")) << binned.dump();
}

// The culling options reach the report, --frustum-baseline adds a frustum-only measurement of
// each culling strategy, and per-pass GPU times name the culling passes when timestamps exist.
TEST(BenchSmokeTest, CullingOptionsAndTheFrustumBaseline) {
    const auto dir = makeTempDir("bench-culling");
    const auto run = runBench(dir,
                              "--scene city --objects 200 --frames 2 --warmup 1 -s "
                              "gpu-culling-bundles --frustum-baseline --lod-error 2.5 "
                              "--width 64 --height 64");
    ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
    ASSERT_FALSE(run.report.is_discarded());
    EXPECT_EQ(run.report["culling"]["occlusion"], true);
    EXPECT_EQ(run.report["culling"]["levelsOfDetail"], true);
    EXPECT_EQ(run.report["culling"]["lodErrorPixels"], 2.5);
    const auto& results = run.report["results"];
    ASSERT_EQ(results.size(), 2u);
    EXPECT_EQ(results[0]["strategy"], "gpu-culling-bundles");
    EXPECT_EQ(results[1]["strategy"], "gpu-culling-bundles (frustum only)");
    if (run.report["timestamps"] == true) {
        EXPECT_TRUE(results[0]["gpuPassesMs"].contains("depth pyramid and culling (second phase)"));
        EXPECT_FALSE(results[1]["gpuPassesMs"].contains("scene (second phase)"));
    }

    const auto off = runBench(dir,
                              "--scene city --objects 200 --frames 2 --warmup 1 -s "
                              "gpu-culling --no-occlusion --no-lod --width 64 --height 64");
    ASSERT_EQ(off.command.exitCode, 0) << off.command.err;
    EXPECT_EQ(off.report["culling"]["occlusion"], false);
    EXPECT_EQ(off.report["culling"]["levelsOfDetail"], false);

    // Without the GPU timer: no GPU times, CPU times still measured.
    const auto untimed = runBench(dir,
                                  "--scene city --objects 200 --frames 2 --warmup 1 -s "
                                  "gpu-culling-bundles --no-gpu-timer --width 64 --height 64");
    ASSERT_EQ(untimed.command.exitCode, 0) << untimed.command.err;
    EXPECT_EQ(untimed.report["timestamps"], false);
    ASSERT_EQ(untimed.report["results"].size(), 1u);
    EXPECT_TRUE(untimed.report["results"][0]["gpuMs"].is_null());
    EXPECT_TRUE(untimed.report["results"][0]["gpuPassesMs"].empty());
    EXPECT_GT(untimed.report["results"][0]["cpuMs"]["median"].get<double>(), 0.0);

    const auto bad = runBench(dir, "--objects 10 --lod-error 0");
    EXPECT_NE(bad.command.exitCode, 0);
    EXPECT_NE(bad.command.err.find("--lod-error"), std::string::npos) << bad.command.err;
}

}  // namespace
}  // namespace encore::test

namespace encore::test {
namespace {

// `encore render --views 2` draws two views side by side from one bundle replayed per view.
TEST(RenderCommandTest, StereoViewsFillBothHalves) {
    const auto dir = makeTempDir("stereo");
    const auto scene = dir / "scene.glb";
    const auto image = dir / "stereo.png";
    ASSERT_EQ(runEncore("gen --objects 20 -o " + quote(scene.string())).exitCode, 0);
    const auto result = runEncore("-v render " + quote(scene.string()) +
                                  " --strategy bundles --views 2 --samples 1 --width 128 "
                                  "--height 64 -o " +
                                  quote(image.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("2 executeBundles in the frame"), std::string::npos) << result.err;
    auto png = image::readImage(image);
    ASSERT_TRUE(png.ok()) << png.error().message;
    ASSERT_EQ(png->width, 128u);
    // Each half has drawn pixels: the corners hold the background.
    const std::uint8_t* background = png->pixel(0, 0);
    for (std::uint32_t half = 0; half < 2; ++half) {
        std::size_t drawn = 0;
        for (std::uint32_t y = 0; y < 64; ++y) {
            for (std::uint32_t x = half * 64; x < half * 64 + 64; ++x) {
                drawn += std::memcmp(png->pixel(x, y), background, 3) != 0;
            }
        }
        EXPECT_GT(drawn, 100u) << "half " << half;
    }
}

// --compute-raster-pixels and --workgroup-raster-pixels move the visibility strategy's split
// between its rasterisers: at 0 and 0 every triangle goes to the hardware; one thread per
// triangle takes the small ones, workgroups then the larger ones.
TEST(BenchSmokeTest, RasterThresholdsMoveTrianglesBetweenRasterisers) {
    struct Split {
        std::string thread, workgroup;
    };
    std::vector<std::uint64_t> computed;
    for (const Split& split : {Split{"0", "0"}, Split{"16", "0"}, Split{"16", "112"}}) {
        SCOPED_TRACE(split.thread + " / " + split.workgroup);
        const auto dir = makeTempDir("bench-raster-" + split.thread + "-" + split.workgroup);
        const auto run =
            runBench(dir,
                     "--scene city --objects 100 --frames 2 --warmup 1 -s visibility "
                     "--width 128 --height 128 --compute-raster-pixels " +
                         split.thread + " --workgroup-raster-pixels " + split.workgroup);
        ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
        ASSERT_FALSE(run.report.is_discarded());
        EXPECT_EQ(run.report["culling"]["computeRasterPixels"], std::stof(split.thread));
        EXPECT_EQ(run.report["culling"]["workgroupRasterPixels"], std::stof(split.workgroup));
        const auto& result = run.report["results"][0];
        ASSERT_GT(result["trianglesDrawn"][0].get<std::uint64_t>(), 0u);
        computed.push_back(result["trianglesCompute"][0].get<std::uint64_t>());
    }
    ASSERT_EQ(computed.size(), 3u);
    EXPECT_EQ(computed[0], 0u);
    EXPECT_LT(computed[0], computed[1]);
    EXPECT_LT(computed[1], computed[2]);
    for (const char* refused : {"--compute-raster-pixels 65", "--workgroup-raster-pixels 8193"}) {
        const auto run = runEncore(std::string("bench --scene city ") + refused);
        EXPECT_EQ(run.exitCode, 2) << refused << ": " << run.err;
    }
}

// A GPU lowers its clocks while the CPU builds a scene: `--warmup-time` repeats the last warm-up
// frame until that long has passed. A CPU adapter (lavapipe here) has no clocks to raise, so by
// default it renders the warm-up frames only; `--warmup 0` means none at all.
TEST(BenchSmokeTest, WarmUpLastsAtLeastTheWarmUpTime) {
    struct Case {
        std::string flags;
        double seconds;
    };
    std::vector<std::uint32_t> warmupFrames;
    for (const Case& c : {Case{"--warmup 2", 0.0}, Case{"--warmup 2 --warmup-time 0.4", 0.4},
                          Case{"--warmup 0 --warmup-time 0.4", 0.0}}) {
        SCOPED_TRACE(c.flags);
        const auto dir = makeTempDir("bench-warmup");
        const auto run = runBench(dir,
                                  "--objects 20 --frames 2 -s materials --width 32 "
                                  "--height 32 " +
                                      c.flags);
        ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
        ASSERT_FALSE(run.report.is_discarded());
        EXPECT_EQ(run.report["warmupSeconds"].get<double>(), c.seconds);
        warmupFrames.push_back(run.report["results"][0]["warmupFrames"].get<std::uint32_t>());
    }
    ASSERT_EQ(warmupFrames.size(), 3u);
    EXPECT_EQ(warmupFrames[0], 2u);
    // A 32x32 frame of 20 objects takes milliseconds: 0.4 s is many more than two.
    EXPECT_GT(warmupFrames[1], 4u);
    EXPECT_EQ(warmupFrames[2], 0u);
    const auto refused = runEncore("bench --objects 20 --warmup-time -1");
    EXPECT_EQ(refused.exitCode, 2) << refused.err;
}

// `--samples 4` measures multisampled frames (the visibility strategy with four visibility
// samples per pixel) and says so in the report; other counts are refused.
TEST(BenchSmokeTest, MeasuresMultisampledFrames) {
    const auto dir = makeTempDir("bench-samples");
    const auto run = runBench(dir,
                              "--objects 50 --frames 2 --warmup 1 -s visibility "
                              "-s gpu-culling-bundles --width 64 --height 64 --samples 4");
    ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
    ASSERT_FALSE(run.report.is_discarded());
    EXPECT_EQ(run.report["target"]["samples"], 4);
    const auto& results = run.report["results"];
    ASSERT_EQ(results.size(), 2u);
    EXPECT_EQ(results[0]["strategy"], "visibility");
    EXPECT_GT(results[0]["trianglesCompute"][0].get<std::uint64_t>(), 0u);
    EXPECT_NE(run.command.out.find("(4 samples per pixel)"), std::string::npos);
    const auto refused = runEncore("bench --objects 50 --samples 2");
    EXPECT_EQ(refused.exitCode, 2) << refused.err;
}

}  // namespace
}  // namespace encore::test
