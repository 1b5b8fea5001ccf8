// `encore bench --smoke` in CI: the benchmark path cannot rot. Checks the report, not speed.

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "CommandRunner.h"
#include "TestPaths.h"

namespace encore::test {
namespace {

TEST(BenchSmokeTest, WritesACompleteReportOnVulkan) {
    const auto dir = makeTempDir("bench-smoke");
    const auto json = dir / "report.json";
    const auto markdown = dir / "report.md";
    const auto result = runEncore("bench --smoke --json " + quote(json.string()) +
                                  " --markdown " + quote(markdown.string()));
    ASSERT_EQ(result.exitCode, 0) << result.err;
    std::ifstream file(json);
    const auto report = nlohmann::json::parse(file, nullptr, false);
    ASSERT_FALSE(report.is_discarded());
    // Numbers from Dawn's Null backend would be meaningless.
    EXPECT_EQ(report["adapter"]["backend"], "Vulkan");
    EXPECT_FALSE(report["adapter"]["name"].get<std::string>().empty());
    EXPECT_NE(report["dawn"], "unknown");
    const auto& results = report["results"];
    ASSERT_EQ(results.size(), 2u * 8u);  // Two scenes, every strategy.
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
        EXPECT_GT(draws, 0u);
    }
    EXPECT_EQ(results[0]["strategy"], "naive");
    EXPECT_EQ(results[0]["frame"]["drawIndexed"], 100);  // One draw per object.
    std::ifstream text(markdown);
    const std::string table((std::istreambuf_iterator<char>(text)), {});
    EXPECT_NE(table.find("| gpu-culling-bundles |"), std::string::npos);
    EXPECT_NE(table.find("Vulkan"), std::string::npos);
}

}  // namespace
}  // namespace encore::test
