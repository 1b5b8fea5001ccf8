// `encore stats`: what the GPU decided to draw, by rasteriser, for the strategies that decide on
// the GPU (GPU culling, the visibility buffer), read back after the counted frame.

#include <gtest/gtest.h>

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "TestPaths.h"

namespace encore::test {
namespace {

TEST(StatsCommandTest, CountsTrianglesByRasteriserWhereTheGpuDecides) {
    const auto dir = makeTempDir("stats-rasterisers");
    const auto scene = dir / "scene.glb";
    const auto generated =
        runEncore("gen --objects 40 --meshes 3 --materials 2 -o " + quote(scene.string()));
    ASSERT_EQ(generated.exitCode, 0) << generated.err;
    const auto result = runEncore("stats " + quote(scene.string()) +
                                  " -s bundles -s gpu-culling -s visibility -s visibility+bundle "
                                  "--json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    std::map<std::string, nlohmann::json> rows;
    const auto report = nlohmann::json::parse(result.out);
    for (const auto& row : report["strategies"]) {
        rows[row["strategy"].get<std::string>()] = row;
    }
    ASSERT_EQ(rows.size(), 4u);
    const auto everything = rows["bundles"]["bundleContents"]["triangles"].get<std::uint64_t>();
    ASSERT_GT(everything, 0u);
    // Drawing what it submits, `bundles` has nothing the GPU decided.
    EXPECT_FALSE(rows["bundles"].contains("gpuTriangles"));

    const auto& culled = rows["gpu-culling"]["gpuTriangles"];
    EXPECT_EQ(culled["compute"], 0);
    EXPECT_GT(culled["hardware"].get<std::uint64_t>(), 0u);
    EXPECT_LE(culled["hardware"].get<std::uint64_t>(), everything);

    for (const char* name : {"visibility", "visibility+bundle"}) {
        SCOPED_TRACE(name);
        const auto& split = rows[name]["gpuTriangles"];
        // The framed scene's small triangles go to compute, and back faces to neither.
        EXPECT_GT(split["compute"].get<std::uint64_t>(), 0u);
        EXPECT_LT(split["compute"].get<std::uint64_t>() + split["hardware"].get<std::uint64_t>(),
                  everything);
    }
    EXPECT_EQ(rows["visibility"]["gpuTriangles"], rows["visibility+bundle"]["gpuTriangles"]);

    const auto table = runEncore("stats " + quote(scene.string()) + " -s visibility");
    ASSERT_EQ(table.exitCode, 0) << table.err;
    EXPECT_NE(table.out.find("| strategy | hardware rasteriser | compute rasteriser |"),
              std::string::npos)
        << table.out;
}

}  // namespace
}  // namespace encore::test
