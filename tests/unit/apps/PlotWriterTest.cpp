#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "TestPaths.h"
#include "bench/BenchmarkReportReader.h"
#include "bench/PlotWriter.h"

namespace encore::bench {
namespace {

using bench::mergeReports;  // `encore plot` merges reports before plotting them.
using nlohmann::json;

json timing(double median, double p95) {
    return json{{"median", median}, {"p95", p95}};
}

// One result as `encore bench` writes it; gpu < 0 stands for "gpuMs": null.
json result(const std::string& scene,
            const std::string& strategy,
            int objects,
            double cpu,
            double gpu = -1.0) {
    return json{{"scene", scene},
                {"label", scene + " " + std::to_string(objects) + " objects"},
                {"objects", objects},
                {"strategy", strategy},
                {"encodeMs", timing(cpu * 0.6, cpu * 0.7)},
                {"submitMs", timing(cpu * 0.4, cpu * 0.5)},
                {"cpuMs", timing(cpu, cpu * 1.2)},
                {"gpuMs", gpu < 0 ? json(nullptr) : timing(gpu, gpu * 1.1)},
                {"frame", {{"setPipeline", objects}, {"drawIndexed", objects}}}};
}

json report(json results, const std::string& adapterName = "llvmpipe (LLVM 15.0.6, 256 bits)") {
    return json{{"encore", "0.1.0"},
                {"date", "2026-11-21T13:45:00Z"},
                {"adapter",
                 {{"name", adapterName},
                  {"backend", "Vulkan"},
                  {"type", "CPU"},
                  {"driver", "Mesa 25.0.7"}}},
                {"dawn", "0.0~git20260909.1a75cb7f-1"},
                {"host", {{"cpu", "test"}, {"cores", 2}}},
                {"frames", 60},
                {"warmup", 10},
                {"timestamps", false},
                {"results", std::move(results)}};
}

std::string plot(const json& input) {
    auto svg = plotScalingSvg(input);
    EXPECT_TRUE(svg.ok()) << (svg.ok() ? "" : svg.error().message);
    return svg.ok() ? *svg : std::string();
}

// A small well-formedness check for the subset of XML the writer emits: every '<' opens a tag,
// closing tags match the innermost open one, and '&' only starts one of the five entities.
::testing::AssertionResult isWellFormed(const std::string& svg) {
    std::vector<std::string> open;
    size_t pos = 0;
    while ((pos = svg.find('<', pos)) != std::string::npos) {
        size_t end = svg.find('>', pos);
        if (end == std::string::npos) {
            return ::testing::AssertionFailure() << "unterminated tag at " << pos;
        }
        std::string tag = svg.substr(pos + 1, end - pos - 1);
        if (tag.find('<') != std::string::npos) {
            return ::testing::AssertionFailure() << "'<' inside tag at " << pos;
        }
        if (!tag.empty() && tag[0] == '/') {
            std::string name = tag.substr(1);
            if (open.empty() || open.back() != name) {
                return ::testing::AssertionFailure()
                       << "</" << name << "> closes <" << (open.empty() ? "" : open.back())
                       << "> at " << pos;
            }
            open.pop_back();
        } else if (tag.empty() || tag.back() != '/') {
            open.push_back(tag.substr(0, tag.find_first_of(" \n\t")));
        }
        pos = end + 1;
    }
    if (!open.empty()) {
        return ::testing::AssertionFailure() << "<" << open.back() << "> is never closed";
    }
    std::regex strayAmpersand("&(?!(amp|lt|gt|quot|apos);)");
    if (std::regex_search(svg, strayAmpersand)) {
        return ::testing::AssertionFailure() << "unescaped '&'";
    }
    return ::testing::AssertionSuccess();
}

size_t countOf(const std::string& text, const std::string& needle) {
    size_t count = 0;
    for (size_t pos = text.find(needle); pos != std::string::npos;
         pos = text.find(needle, pos + needle.size())) {
        ++count;
    }
    return count;
}

// The text of each <g class="panel"> in order.
std::vector<std::string> panels(const std::string& svg) {
    const std::string marker = "<g class=\"panel\">";
    std::vector<std::string> out;
    for (size_t pos = svg.find(marker); pos != std::string::npos;) {
        size_t next = svg.find(marker, pos + marker.size());
        size_t legend = svg.find("<g class=\"legend\">", pos);
        out.push_back(svg.substr(pos, std::min(next, legend) - pos));
        pos = next;
    }
    return out;
}

// The (x, y) vertices of a series' polyline within one panel; empty when the series has none.
std::vector<std::pair<double, double>> polyline(const std::string& panel,
                                                const std::string& series) {
    size_t group = panel.find("data-series=\"" + series + "\"");
    if (group == std::string::npos) {
        return {};
    }
    size_t start = panel.find("points=\"", panel.find("<polyline", group)) + 8;
    std::string points = panel.substr(start, panel.find('"', start) - start);
    std::vector<std::pair<double, double>> vertices;
    std::regex pair("(-?[0-9.]+),(-?[0-9.]+)");
    for (std::sregex_iterator it(points.begin(), points.end(), pair), end; it != end; ++it) {
        vertices.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
    }
    return vertices;
}

json scalingResults() {
    return json::array(
        {result("generated", "naive", 100, 0.5), result("generated", "naive", 1000, 2.0),
         result("generated", "naive", 10000, 18.0), result("generated", "bundles", 100, 0.3),
         result("generated", "bundles", 1000, 0.9), result("generated", "bundles", 10000, 6.0),
         result("generated", "instancing", 1000, 0.2),
         result("generated", "instancing", 10000, 0.4), result("model", "naive", 6, 1.0),
         result("animometer", "animometer-bundle", 20000, 4.0)});
}

TEST(PlotWriterTest, OutputIsOneWellFormedSvgElement) {
    std::string svg = plot(report(scalingResults()));
    EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
    while (!svg.empty() && svg.back() == '\n') {
        svg.pop_back();
    }
    EXPECT_TRUE(svg.ends_with("</svg>"));
    EXPECT_EQ(countOf(svg, "<svg"), 1u);
    EXPECT_TRUE(isWellFormed(svg));
    EXPECT_NE(svg.find("width=\"900\" height=\"560\""), std::string::npos);
}

TEST(PlotWriterTest, CheckerRejectsBrokenMarkup) {
    EXPECT_FALSE(isWellFormed("<svg><g></svg>"));
    EXPECT_FALSE(isWellFormed("<svg><text>a < b</text></svg>"));
    EXPECT_FALSE(isWellFormed("<svg><text>AT&T</text></svg>"));
    EXPECT_TRUE(isWellFormed("<svg><g><line/></g><text>AT&amp;T</text></svg>"));
}

TEST(PlotWriterTest, OnePolylinePerStrategyWithOnePointPerResult) {
    const std::string svg = plot(report(scalingResults()));
    auto all = panels(svg);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(countOf(all[0], "<polyline"), 4u);
    EXPECT_EQ(polyline(all[0], "naive").size(), 3u);
    EXPECT_EQ(polyline(all[0], "bundles").size(), 3u);
    EXPECT_EQ(polyline(all[0], "instancing").size(), 2u);
    EXPECT_EQ(polyline(all[0], "animometer-bundle").size(), 1u);
    // Every plotted point has a marker; the model result (6 objects) is not plotted.
    EXPECT_EQ(countOf(all[0], "class=\"marker\""), 9u);
    EXPECT_EQ(countOf(all[0], "class=\"p95\""), 9u);
}

TEST(PlotWriterTest, ObjectCountsAreLogSpacedAndSorted) {
    // Report order is shuffled: the writer sorts by object count.
    const std::string svg = plot(report(json::array({result("generated", "naive", 100000, 50.0),
                                                     result("generated", "naive", 1000, 1.0),
                                                     result("generated", "naive", 10000, 5.0)})));
    auto points = polyline(panels(svg).at(0), "naive");
    ASSERT_EQ(points.size(), 3u);
    EXPECT_LT(points[0].first, points[1].first);
    EXPECT_LT(points[1].first, points[2].first);
    EXPECT_NEAR(points[1].first - points[0].first, points[2].first - points[1].first, 0.15);
    // Decade labels cover the range.
    for (const char* label : {">1k<", ">10k<", ">100k<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
}

TEST(PlotWriterTest, TwiceTheTimeIsLog2OfADecadeHigher) {
    const std::string svg = plot(report(
        json::array({result("generated", "naive", 10, 1.0), result("generated", "naive", 100, 2.0),
                     result("generated", "naive", 1000, 10.0)})));
    auto points = polyline(panels(svg).at(0), "naive");
    ASSERT_EQ(points.size(), 3u);
    const double decade = points[0].second - points[2].second;  // 1 ms -> 10 ms, y grows down.
    ASSERT_GT(decade, 50.0);
    EXPECT_NEAR((points[0].second - points[1].second) / decade, std::log10(2.0), 0.002);
    // The y labels span the data: 1 ms up to 10 ms p95 (12 ms) needs the 100 ms decade.
    for (const char* label : {">1<", ">10<", ">100<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
}

TEST(PlotWriterTest, SmallTimesGetFractionalDecadeLabels) {
    const std::string svg = plot(report(json::array(
        {result("generated", "naive", 10, 0.02), result("generated", "naive", 100, 0.5)})));
    for (const char* label : {">0.01<", ">0.1<", ">1<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
}

TEST(PlotWriterTest, LegendNamesEveryStrategyOnce) {
    const std::string svg = plot(report(scalingResults()));
    const std::string legend = svg.substr(svg.find("<g class=\"legend\">"));
    for (const char* name : {"naive", "bundles", "instancing", "animometer-bundle"}) {
        EXPECT_EQ(countOf(legend, std::string(">") + name + "</text>"), 1u) << name;
    }
}

TEST(PlotWriterTest, SeriesLookDifferentInColourAndShape) {
    const std::string svg = plot(report(scalingResults()));
    const std::string legend = svg.substr(svg.find("<g class=\"legend\">"));
    std::regex stroke("<g stroke=\"(#[0-9a-f]{6})\"");
    std::vector<std::string> colours;
    for (std::sregex_iterator it(legend.begin(), legend.end(), stroke), end; it != end; ++it) {
        colours.push_back((*it)[1]);
    }
    ASSERT_EQ(colours.size(), 4u);
    std::sort(colours.begin(), colours.end());
    EXPECT_EQ(std::unique(colours.begin(), colours.end()), colours.end());
    // Greyscale: the first series are told apart by marker element and dash pattern too.
    EXPECT_NE(legend.find("<circle"), std::string::npos);
    EXPECT_NE(legend.find("<polygon"), std::string::npos);
    EXPECT_NE(legend.find("stroke-dasharray"), std::string::npos);
}

TEST(PlotWriterTest, EscapesXmlInText) {
    const std::string svg =
        plot(report(json::array({result("generated", "a<b>&\"c\"", 10, 1.0)}), "AT&T <GPU>"));
    EXPECT_TRUE(isWellFormed(svg));
    EXPECT_NE(svg.find("AT&amp;T &lt;GPU&gt; (Vulkan), 2026-11-21T13:45:00Z"), std::string::npos);
    EXPECT_EQ(svg.find("<GPU>"), std::string::npos);
    EXPECT_NE(svg.find(">a&lt;b&gt;&amp;&quot;c&quot;</text>"), std::string::npos);
}

TEST(PlotWriterTest, GpuPanelOnlyWithGpuTimings) {
    const std::string cpuOnly = plot(report(scalingResults()));
    EXPECT_EQ(panels(cpuOnly).size(), 1u);
    EXPECT_NE(cpuOnly.find("CPU time per frame (encode + submit), median"), std::string::npos);
    EXPECT_EQ(cpuOnly.find("GPU time per frame"), std::string::npos);

    json results = scalingResults();
    results[1] = result("generated", "naive", 1000, 2.0, 3.1);
    const std::string withGpu = plot(report(results));
    auto all = panels(withGpu);
    ASSERT_EQ(all.size(), 2u);
    EXPECT_NE(all[1].find("GPU time per frame, median"), std::string::npos);
    EXPECT_EQ(polyline(all[1], "naive").size(), 1u);
    EXPECT_EQ(countOf(all[1], "<polyline"), 1u);  // Only naive has a GPU time.
    EXPECT_EQ(polyline(all[0], "naive").size(), 3u);
    EXPECT_TRUE(isWellFormed(withGpu));
}

TEST(PlotWriterTest, NonPositiveAndNonFiniteValuesAreSkipped) {
    const std::string svg = plot(report(json::array(
        {result("generated", "naive", 10, 1.0), result("generated", "naive", 100, 0.0),
         result("generated", "naive", 0, 3.0), result("generated", "naive", 200, -1.0),
         result("generated", "naive", 300, std::nan("")),
         result("generated", "naive", 400, HUGE_VAL), result("generated", "naive", 1000, 4.0)})));
    EXPECT_EQ(polyline(panels(svg).at(0), "naive").size(), 2u);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
    EXPECT_TRUE(isWellFormed(svg));
}

TEST(PlotWriterTest, AnimometerIsItsOwnSeriesEvenWithAGeneratedStrategyName) {
    const std::string svg = plot(report(json::array(
        {result("generated", "bundles", 10, 1.0), result("generated", "bundles", 100, 2.0),
         result("animometer", "bundles", 20000, 5.0)})));
    auto all = panels(svg);
    EXPECT_EQ(polyline(all.at(0), "bundles").size(), 2u);
    EXPECT_EQ(polyline(all.at(0), "animometer bundles").size(), 1u);
    EXPECT_NE(svg.find(">animometer bundles</text>"), std::string::npos);
}

TEST(PlotWriterTest, FallsBackToEncodePlusSubmit) {
    json entry = result("generated", "naive", 1000, 2.0);
    entry.erase("cpuMs");
    const std::string svg = plot(report(json::array({entry})));
    // encode 1.2 + submit 0.8; p95 1.4 + 1.0.
    EXPECT_NE(svg.find("naive: 1000 objects, median 2.000 ms, p95 2.400 ms"), std::string::npos);
}

TEST(PlotWriterTest, MissingResultsIsAnError) {
    json input = report(json::array());
    input.erase("results");
    auto svg = plotScalingSvg(input);
    ASSERT_FALSE(svg.ok());
    EXPECT_EQ(svg.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(svg.error().message.find("results"), std::string::npos);

    EXPECT_FALSE(plotScalingSvg(json::array()).ok());
    EXPECT_FALSE(plotScalingSvg(report(json::array())).ok());  // Nothing to plot.
    auto modelsOnly = plotScalingSvg(report(json::array({result("model", "naive", 6, 1.0)})));
    ASSERT_FALSE(modelsOnly.ok());
    EXPECT_NE(modelsOnly.error().message.find("generated"), std::string::npos);
}

TEST(PlotWriterTest, MalformedResultNamesTheResultAndField) {
    json entry = result("generated", "naive", 1000, 2.0);
    entry.erase("cpuMs");
    entry.erase("submitMs");
    auto svg = plotScalingSvg(report(json::array({result("generated", "naive", 10, 1.0), entry})));
    ASSERT_FALSE(svg.ok());
    EXPECT_NE(svg.error().message.find("result 1 ('generated 1000 objects')"), std::string::npos)
        << svg.error().message;
    EXPECT_NE(svg.error().message.find("submitMs"), std::string::npos);

    json noStrategy = result("generated", "naive", 10, 1.0);
    noStrategy.erase("strategy");
    svg = plotScalingSvg(report(json::array({noStrategy})));
    ASSERT_FALSE(svg.ok());
    EXPECT_NE(svg.error().message.find("\"strategy\""), std::string::npos);

    json input = report(scalingResults());
    input.erase("adapter");
    svg = plotScalingSvg(input);
    ASSERT_FALSE(svg.ok());
    EXPECT_NE(svg.error().message.find("adapter"), std::string::npos);
}

TEST(PlotWriterTest, SameReportGivesSameBytes) {
    const json input = report(scalingResults());
    const std::string first = plot(input);
    EXPECT_EQ(first, plot(input));
    EXPECT_EQ(first, plot(json::parse(input.dump())));
}

TEST(PlotWriterTest, SelfContainedAndNeedsNoConverter) {
    // rsvg-convert (librsvg2-bin) may come later for PNGs; the SVG itself must not need it, nor
    // anything else on PATH.
    const char* oldPath = std::getenv("PATH");
    const std::string savedPath = oldPath ? oldPath : "";
    const auto emptyDir = test::makeTempDir("plot-empty-path");
    ASSERT_EQ(setenv("PATH", emptyDir.c_str(), 1), 0);
    auto svg = plotScalingSvg(report(scalingResults()));
    setenv("PATH", savedPath.c_str(), 1);
    ASSERT_TRUE(svg.ok());
    for (const char* external : {"href", "<script", "<image", "@import", "url("}) {
        EXPECT_EQ(svg->find(external), std::string::npos) << external;
    }
}

// Crowd results plot over their character counts, one series per (evaluation, strategy), so the
// CPU and GPU animation paths of one strategy are two curves.
TEST(PlotWriterTest, CrowdsAreSeriesPerAnimationPath) {
    json results = json::array();
    for (int characters : {1000, 10000, 100000}) {
        for (const char* animation : {"cpu", "gpu"}) {
            json entry = result("crowd", "bundles", characters,
                                std::string(animation) == "cpu" ? characters * 0.001 : 0.1);
            entry["animation"] = animation;
            results.push_back(entry);
        }
    }
    const std::string svg = plot(report(results));
    const auto all = panels(svg);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(polyline(all.at(0), "cpu-animated bundles").size(), 3u);
    EXPECT_EQ(polyline(all.at(0), "gpu-animated bundles").size(), 3u);
    EXPECT_NE(svg.find(">gpu-animated bundles</text>"), std::string::npos);
}

// A generated walkthrough ("flythrough" or "city") as `encore bench --scene` writes it; drawn
// empty stands for "trianglesDrawn": null (a strategy without GPU culling).
json walkthrough(const std::string& scene,
                 const std::string& strategy,
                 int objects,
                 double gpu,
                 std::vector<int> submitted,
                 std::vector<int> drawn = {}) {
    json entry = result(scene, strategy, objects, 0.3, gpu);
    entry["trianglesSubmitted"] = submitted;
    entry["trianglesDrawn"] = drawn.empty() ? json(nullptr) : json(drawn);
    return entry;
}

TEST(PlotWriterTest, WalkthroughsAreSeriesPerSceneAndStrategy) {
    json results = json::array();
    for (int objects : {100000, 1000000}) {
        for (const char* scene : {"flythrough", "city"}) {
            results.push_back(walkthrough(scene, "bundles", objects, objects * 1e-5, {}));
            results.push_back(walkthrough(scene, "gpu-culling-bundles", objects, 2.0, {}, {}));
        }
    }
    const std::string svg = plot(report(results));
    EXPECT_TRUE(isWellFormed(svg));
    const auto all = panels(svg);
    ASSERT_EQ(all.size(), 2u);  // No triangle counts: CPU and GPU only.
    for (const std::string& panel : all) {
        for (const char* series : {"flythrough: bundles", "flythrough: gpu-culling-bundles",
                                   "city: bundles", "city: gpu-culling-bundles"}) {
            EXPECT_EQ(polyline(panel, series).size(), 2u) << series;
        }
    }
    // GPU time of bundles grows tenfold from 100k to 1M objects: one decade up, x one decade on.
    const auto bundles = polyline(all[1], "city: bundles");
    const auto culling = polyline(all[1], "city: gpu-culling-bundles");
    EXPECT_LT(bundles[0].first, bundles[1].first);
    EXPECT_GT(bundles[0].second, bundles[1].second);
    EXPECT_DOUBLE_EQ(culling[0].second, culling[1].second);
    EXPECT_NE(svg.find(">flythrough: gpu-culling-bundles</text>"), std::string::npos);
    EXPECT_EQ(svg.find("Triangles per frame"), std::string::npos);
}

TEST(PlotWriterTest, TrianglesPanelShowsMedianDrawnElseSubmittedWithWhiskerToMax) {
    const json results =
        json::array({walkthrough("city", "bundles", 100000, 4.0, {3000000, 3000000, 3000000}),
                     walkthrough("city", "gpu-culling-bundles", 100000, 0.8,
                                 {3000000, 3000000, 3000000}, {30000, 50000, 20000, 40000}),
                     walkthrough("city", "gpu-culling-bundles", 1000000, 0.9, {30000000},
                                 {100000, 300000, 200000}),
                     result("generated", "naive", 1000, 2.0, 3.0)});
    const std::string svg = plot(report(results));
    EXPECT_TRUE(isWellFormed(svg));
    EXPECT_NE(svg.find("width=\"1320\""), std::string::npos);
    const auto all = panels(svg);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_NE(all[2].find("Triangles per frame, median"), std::string::npos);
    EXPECT_EQ(polyline(all[2], "naive").size(), 0u);  // No triangle counts.
    const auto bundles = polyline(all[2], "city: bundles");
    const auto culling = polyline(all[2], "city: gpu-culling-bundles");
    ASSERT_EQ(bundles.size(), 1u);
    ASSERT_EQ(culling.size(), 2u);
    // Medians 3M (submitted), 35k (the mean of the middle two drawn) and 200k, on a log y axis.
    EXPECT_DOUBLE_EQ(culling[0].first, bundles[0].first);
    const double rise = culling[0].second - culling[1].second;
    const double toSubmitted = culling[0].second - bundles[0].second;
    EXPECT_NEAR(rise / toSubmitted, std::log10(200000.0 / 35000) / std::log10(3000000.0 / 35000),
                0.01);
    EXPECT_NE(all[2].find("city: gpu-culling-bundles: 100000 objects, median 35000 triangles, "
                          "max 50000 triangles"),
              std::string::npos);
    EXPECT_NE(all[2].find("city: bundles: 100000 objects, median 3000000 triangles, max "
                          "3000000 triangles"),
              std::string::npos);
    EXPECT_NE(all[2].find("city: gpu-culling-bundles: 1000000 objects, median 200000 triangles"),
              std::string::npos);
    EXPECT_GT(culling[0].second, bundles[0].second);            // Fewer triangles sit lower.
    EXPECT_NE(all[2].find(">100k</text>"), std::string::npos);  // Count labels on y as well.
    EXPECT_NE(svg.find("(triangles: to max)"), std::string::npos);
    EXPECT_EQ(plot(report(results)), svg);
}

TEST(PlotWriterTest, NonNumericTriangleCountIsAnError) {
    json entry = walkthrough("city", "bundles", 1000, 1.0, {10, 20});
    entry["trianglesSubmitted"][1] = "many";
    auto svg = plotScalingSvg(report(json::array({entry})));
    ASSERT_FALSE(svg.ok());
    EXPECT_NE(svg.error().message.find("'city 1000 objects'"), std::string::npos)
        << svg.error().message;
    EXPECT_NE(svg.error().message.find("\"trianglesSubmitted\""), std::string::npos);
}

TEST(PlotWriterTest, MergedReportsConcatenateResults) {
    const json small = report(json::array({walkthrough("city", "bundles", 100000, 4.0, {})}));
    json large = report(json::array({walkthrough("city", "bundles", 1000000, 33.0, {})}));
    large["date"] = "2026-11-22T10:00:00Z";
    auto merged = mergeReports({{"small.json", small}, {"large.json", large}});
    ASSERT_TRUE(merged.ok()) << merged.error().message;
    ASSERT_EQ((*merged)["results"].size(), 2u);
    EXPECT_EQ((*merged)["results"][1]["objects"], 1000000);
    EXPECT_EQ((*merged)["date"], small["date"]);  // Everything else is the first report's.
    const std::string svg = plot(*merged);
    EXPECT_EQ(polyline(panels(svg).at(1), "city: bundles").size(), 2u);

    auto single = mergeReports({{"small.json", small}});
    ASSERT_TRUE(single.ok());
    EXPECT_EQ(*single, small);
}

TEST(PlotWriterTest, MergingReportsOfDifferentAdaptersIsAnError) {
    const json a = report(json::array({result("generated", "naive", 10, 1.0)}));
    const json b = report(json::array({result("generated", "naive", 100, 2.0)}), "Other GPU");
    auto merged = mergeReports({{"a.json", a}, {"b.json", b}});
    ASSERT_FALSE(merged.ok());
    EXPECT_EQ(merged.error().code, ErrorCode::InvalidFormat);
    EXPECT_NE(merged.error().message.find("b.json"), std::string::npos) << merged.error().message;
    EXPECT_NE(merged.error().message.find("Other GPU"), std::string::npos);

    json noResults = a;
    noResults.erase("results");
    auto broken = mergeReports({{"a.json", a}, {"c.json", noResults}});
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.error().message.find("c.json"), std::string::npos);
    EXPECT_FALSE(mergeReports({}).ok());
}

}  // namespace
}  // namespace encore::bench
