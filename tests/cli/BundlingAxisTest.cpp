// The bundling axis from the command line: any strategy recorded once into a render bundle
// (`--bundle`, or `-s NAME+bundle`) in render, stats and bench; a naive frame replayed from a
// bundle is the Animometer case on real scenes.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

std::filesystem::path generatedScene(const std::filesystem::path& dir, int objects) {
    const auto scene = dir / "scene.glb";
    const auto generated = runEncore("gen --objects " + std::to_string(objects) +
                                     " --meshes 3 --materials 2 -o " + quote(scene.string()));
    EXPECT_EQ(generated.exitCode, 0) << generated.err;
    return scene;
}

std::uint64_t drawsIn(const nlohmann::json& counters) {
    return counters["draw"].get<std::uint64_t>() + counters["drawIndexed"].get<std::uint64_t>() +
           counters["drawIndirect"].get<std::uint64_t>();
}

TEST(BundlingAxisTest, StatsCountEachStrategyDirectAndRecordedIntoABundle) {
    const auto dir = makeTempDir("bundling-stats");
    const auto scene = generatedScene(dir, 30);
    const auto result = runEncore("stats " + quote(scene.string()) +
                                  " -s naive -s instancing -s materials --bundle --json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto report = nlohmann::json::parse(result.out);
    std::map<std::string, nlohmann::json> rows;
    std::vector<std::string> order;
    for (const auto& row : report["strategies"]) {
        order.push_back(row["strategy"].get<std::string>());
        rows[order.back()] = row;
    }
    // Each direct strategy followed by its bundled form; materials bundled is `bundles`.
    EXPECT_EQ(order, (std::vector<std::string>{"naive", "naive+bundle", "instancing",
                                               "instancing+bundle", "materials", "bundles"}));
    for (const std::string direct : {"naive", "instancing", "materials"}) {
        const std::string bundled = direct == "materials" ? "bundles" : direct + "+bundle";
        SCOPED_TRACE(bundled);
        const auto& directRow = rows[direct];
        const auto& bundledRow = rows[bundled];
        EXPECT_EQ(directRow["frame"]["executeBundles"], 0);
        EXPECT_EQ(directRow["bundlesRecorded"], 0);
        EXPECT_EQ(bundledRow["bundlesRecorded"], 1);
        EXPECT_EQ(bundledRow["frame"]["executeBundles"], 1);
        EXPECT_EQ(drawsIn(bundledRow["frame"]), 0u);
        // The bundle holds what the direct frame draws.
        EXPECT_EQ(drawsIn(bundledRow["bundleContents"]), drawsIn(directRow["frame"]));
        EXPECT_EQ(bundledRow["bundleContents"]["triangles"], directRow["frame"]["triangles"]);
    }
    EXPECT_EQ(drawsIn(rows["naive"]["frame"]), 30u);  // One draw per object.
    EXPECT_EQ(rows["naive+bundle"]["bundleContents"]["setPipeline"],
              rows["naive"]["frame"]["setPipeline"]);
}

TEST(BundlingAxisTest, ABundledFrameRendersTheDirectFramesPixels) {
    const auto dir = makeTempDir("bundling-render");
    const auto scene = generatedScene(dir, 40);
    const std::string common = " --width 64 --height 64 --samples 1 -o ";
    for (const auto& [name, options] :
         std::map<std::string, std::string>{{"direct", "-s naive"},
                                            {"flag", "-s naive --bundle"},
                                            {"named", "-s naive+bundle"},
                                            {"pipeline-cache", "-s pipeline-cache --bundle"}}) {
        const auto result = runEncore("-v render " + quote(scene.string()) + " " + options +
                                      common + quote((dir / (name + ".png")).string()));
        ASSERT_EQ(result.exitCode, 0) << result.err;
        if (name != "direct") {
            EXPECT_NE(result.err.find("+bundle: 0 draws and 1 executeBundles"), std::string::npos)
                << result.err;
        }
    }
    const auto direct = image::readImage(dir / "direct.png");
    ASSERT_TRUE(direct.ok());
    for (const char* name : {"flag", "named", "pipeline-cache"}) {
        SCOPED_TRACE(name);
        const auto bundled = image::readImage(dir / (std::string(name) + ".png"));
        ASSERT_TRUE(bundled.ok());
        EXPECT_EQ(bundled->pixels, direct->pixels);
    }
}

TEST(BundlingAxisTest, BenchMeasuresANaiveFrameReplayedFromABundle) {
    const auto run = runBench(makeTempDir("bundling-bench"),
                              "--objects 50 -s naive -s gpu-culling --bundle --frames 2 "
                              "--warmup 1 --width 32 --height 32");
    ASSERT_EQ(run.command.exitCode, 0) << run.command.err;
    ASSERT_FALSE(run.report.is_discarded());
    const auto& results = run.report["results"];
    ASSERT_EQ(results.size(), 4u);
    EXPECT_EQ(results[0]["strategy"], "naive");
    EXPECT_EQ(results[1]["strategy"], "naive+bundle");
    EXPECT_EQ(results[2]["strategy"], "gpu-culling");
    EXPECT_EQ(results[3]["strategy"], "gpu-culling-bundles");
    EXPECT_EQ(drawsIn(results[0]["frame"]), 50u);
    EXPECT_EQ(results[1]["frame"]["executeBundles"], 1);
    EXPECT_EQ(drawsIn(results[1]["frame"]), 0u);
    EXPECT_EQ(drawsIn(results[1]["bundleContents"]), 50u);
    EXPECT_GT(results[1]["cpuMs"]["median"].get<double>(), 0.0);
}

TEST(BundlingAxisTest, AStrategyWithABundledKindOfItsOwnHasNoPlusBundleName) {
    const auto dir = makeTempDir("bundling-names");
    const auto scene = generatedScene(dir, 4);
    for (const char* name : {"bundles+bundle", "materials+bundle", "naive+bundles", "+bundle"}) {
        SCOPED_TRACE(name);
        const auto result = runEncore("stats " + quote(scene.string()) + " -s " + name);
        EXPECT_EQ(result.exitCode, 2);  // A usage error.
        EXPECT_NE(result.err.find("Unknown strategy '" + std::string(name) + "'"),
                  std::string::npos)
            << result.err;
        EXPECT_NE(result.err.find("naive+bundle"), std::string::npos) << result.err;
    }
}

}  // namespace
}  // namespace encore::test
