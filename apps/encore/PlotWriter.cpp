#include "PlotWriter.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

namespace encore::app {
namespace {

using nlohmann::json;

constexpr double kWidth = 900.0;
constexpr double kWideWidth = 1320.0;  // Three panels side by side.
constexpr double kMinHeight = 560.0;
constexpr double kMinPlotHeight = 250.0;
constexpr double kPlotTop = 78.0;
constexpr int kLegendColumns = 4;
constexpr double kLegendRowHeight = 18.0;

// Ten hues that stay apart for the common colour-vision deficiencies; greyscale printouts rely
// on the marker shapes and dash patterns below, which cycle with different periods.
constexpr std::array<std::string_view, 10> kPalette = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                       "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                       "#bcbd22", "#17becf"};
constexpr std::array<std::string_view, 4> kDashes = {"", "6 3", "2 3", "8 3 2 3"};

// Marker outlines around the point, in pixels; an empty outline is a circle. Six shapes against
// four dash patterns give twelve series that differ in greyscale.
using Outline = std::vector<std::pair<double, double>>;
const std::array<Outline, 6> kMarkers = {
    Outline{},
    Outline{{-3.2, -3.2}, {3.2, -3.2}, {3.2, 3.2}, {-3.2, 3.2}},
    Outline{{0, -4.5}, {4.2, 3.2}, {-4.2, 3.2}},
    Outline{{0, -4.5}, {4.5, 0}, {0, 4.5}, {-4.5, 0}},
    Outline{{0, 4.5}, {4.2, -3.2}, {-4.2, -3.2}},
    Outline{{-4.2, -4.2}, {4.2, 4.2}, {4.2, -4.2}, {-4.2, 4.2}}};  // A bow tie.

// A median and where its whisker ends: the p95 for times, the maximum for triangle counts.
struct Spread {
    double median = 0.0;
    double high = 0.0;  // 0 when the report has none: no whisker is drawn.
};

struct Point {
    double objects = 0.0;
    Spread cpu;
    std::optional<Spread> gpu;
    std::optional<Spread> triangles;  // Per frame: drawn after GPU culling, else submitted.
};

// What a panel's y axis shows.
enum class Quantity {
    CpuMs,
    GpuMs,
    Triangles,
};

struct Series {
    std::string scene;
    std::string animation;  // Crowds: "cpu" or "gpu", where the animation was evaluated.
    std::string strategy;
    std::string label;
    std::vector<Point> points;
};

// A log10 axis spanning whole decades [low, high], mapped onto [pixelLow, pixelHigh].
struct LogAxis {
    int low = 0;
    int high = 1;
    double pixelLow = 0.0;
    double pixelHigh = 1.0;

    double map(double value) const {
        return pixelLow + (std::log10(value) - low) / (high - low) * (pixelHigh - pixelLow);
    }
};

// Fixed notation through to_chars, because printf-style formatting follows the process locale
// and a decimal comma would corrupt the SVG.
std::string number(double value, int precision = 1) {
    std::array<char, 64> buffer{};
    auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                   std::chars_format::fixed, precision);
    std::string text(buffer.data(), ec == std::errc() ? end : buffer.data());
    // -0.0 and 0.0 are the same coordinate; print them alike so output stays byte-stable.
    if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) {
        text.erase(0, 1);
    }
    return text;
}

std::string escapeXml(std::string_view text) {
    constexpr std::string_view kSpecial = "&<>\"'";
    constexpr std::array<std::string_view, 5> kEntities = {"&amp;", "&lt;", "&gt;", "&quot;",
                                                           "&apos;"};
    std::string out;
    for (char c : text) {
        if (size_t i = kSpecial.find(c); i != std::string_view::npos) {
            out += kEntities[i];
        } else {
            // XML 1.0 forbids most control characters, even as character references.
            out += (static_cast<unsigned char>(c) < 0x20 && c != '\t') ? ' ' : c;
        }
    }
    return out;
}

std::string decadeLabel(int exponent, bool isCount) {
    if (exponent < 0) {
        return "0." + std::string(static_cast<size_t>(-exponent - 1), '0') + "1";
    }
    if (isCount && exponent >= 3 && exponent < 9) {
        return "1" + std::string(static_cast<size_t>(exponent % 3), '0') +
               (exponent < 6 ? "k" : "M");
    }
    return "1" + std::string(static_cast<size_t>(exponent), '0');
}

// The smallest whole-decade range holding every positive value; the epsilon keeps exact powers
// of ten (1000 objects) on a gridline instead of opening a spare decade.
std::pair<int, int> decadeRange(const std::vector<double>& values) {
    if (values.empty()) {
        return {0, 1};
    }
    auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    int low = static_cast<int>(std::floor(std::log10(*lo) + 1e-9));
    int high = static_cast<int>(std::ceil(std::log10(*hi) - 1e-9));
    return {low, std::max(high, low + 1)};
}

std::string describe(const json& result, size_t index) {
    std::string text = "Benchmark result " + std::to_string(index);
    if (result.contains("label") && result["label"].is_string()) {
        text += " ('" + result["label"].get<std::string>() + "')";
    }
    return text;
}

std::optional<double> numberAt(const json& object, const char* pointer) {
    const json::json_pointer at(pointer);
    if (!object.contains(at) || !object[at].is_number()) {
        return std::nullopt;
    }
    return object[at].get<double>();
}

// A per-frame array of counts; missing and null read as empty. The error message is completed
// by the caller, which knows which result this is.
Result<std::vector<double>> readCounts(const json& result, const char* key) {
    std::vector<double> counts;
    auto it = result.find(key);
    if (it == result.end() || it->is_null()) {
        return counts;
    }
    if (!it->is_array()) {
        return makeError(ErrorCode::InvalidFormat,
                         "has a \"" + std::string(key) + "\" that is neither an array nor null");
    }
    for (const json& count : *it) {
        if (!count.is_number()) {
            return makeError(ErrorCode::InvalidFormat,
                             "has a non-numeric entry in \"" + std::string(key) + "\"");
        }
        counts.push_back(count.get<double>());
    }
    return counts;
}

// The median (the mean of the middle two for an even count) and the maximum.
Spread summarize(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t middle = values.size() / 2;
    const double median =
        values.size() % 2 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
    return {median, values.back()};
}

// The error message is completed by the caller, which knows which result this is.
Result<Point> readPoint(const json& result) {
    const auto objects = numberAt(result, "/objects");
    if (!objects) {
        return makeError(ErrorCode::InvalidFormat, "has no numeric \"objects\" count");
    }
    Point point{*objects, {}, {}, {}};
    if (auto cpu = numberAt(result, "/cpuMs/median")) {
        point.cpu = {*cpu, numberAt(result, "/cpuMs/p95").value_or(0.0)};
    } else {
        // Reports may only split CPU time into encode and submit; the sum of their p95s bounds
        // the p95 of the sum from above.
        auto encode = numberAt(result, "/encodeMs/median");
        auto submit = numberAt(result, "/submitMs/median");
        if (!encode || !submit) {
            return makeError(ErrorCode::InvalidFormat,
                             "has neither \"cpuMs.median\" nor both \"encodeMs.median\" and "
                             "\"submitMs.median\"");
        }
        point.cpu = {*encode + *submit, numberAt(result, "/encodeMs/p95").value_or(0.0) +
                                            numberAt(result, "/submitMs/p95").value_or(0.0)};
    }
    // "gpuMs": null means the adapter had no timestamp queries.
    if (result.contains("gpuMs") && !result["gpuMs"].is_null()) {
        auto gpu = numberAt(result, "/gpuMs/median");
        if (!gpu) {
            return makeError(ErrorCode::InvalidFormat, "has no numeric \"gpuMs.median\"");
        }
        point.gpu = Spread{*gpu, numberAt(result, "/gpuMs/p95").value_or(0.0)};
    }
    // Strategies without GPU culling draw what they submit and report "trianglesDrawn": null.
    for (const char* key : {"trianglesDrawn", "trianglesSubmitted"}) {
        auto counts = readCounts(result, key);
        if (!counts) {
            return counts.error();
        }
        if (!counts->empty()) {
            point.triangles = summarize(*counts);
            break;
        }
    }
    return point;
}

Result<std::vector<Series>> readSeries(const json& results) {
    std::vector<Series> series;
    for (size_t i = 0; i < results.size(); ++i) {
        const json& result = results[i];
        if (!result.is_object() || !result.contains("scene") || !result["scene"].is_string()) {
            return makeError(ErrorCode::InvalidFormat,
                             "Benchmark result " + std::to_string(i) + " has no \"scene\" string.");
        }
        const std::string scene = result["scene"].get<std::string>();
        const bool walkthrough = scene == "flythrough" || scene == "city";
        if (scene != "generated" && scene != "animometer" && scene != "crowd" && !walkthrough) {
            continue;  // Single models have no object-count axis.
        }
        const std::string animation = result.contains("animation") && result["animation"].is_string()
                                          ? result["animation"].get<std::string>()
                                          : std::string();
        if (!result.contains("strategy") || !result["strategy"].is_string()) {
            return makeError(ErrorCode::InvalidFormat,
                             describe(result, i) + " has no \"strategy\" string.");
        }
        auto point = readPoint(result);
        if (!point) {
            return makeError(point.error().code,
                             describe(result, i) + " " + point.error().message + ".");
        }
        const std::string strategy = result["strategy"].get<std::string>();
        auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) {
            return s.scene == scene && s.animation == animation && s.strategy == strategy;
        });
        if (it == series.end()) {
            // A crowd's axis counts characters; its series say where the animation ran.
            // Generated walkthroughs share strategy names; the scene tells their curves apart.
            const std::string label =
                scene == "crowd"
                    ? (animation.empty() ? std::string("still") : animation + "-animated") + " " +
                          strategy
                : walkthrough ? scene + ": " + strategy
                              : strategy;
            it = series.insert(series.end(), Series{scene, animation, strategy, label, {}});
        }
        it->points.push_back(*point);
    }
    // Generated scenes first (they are the scaling study), animometer after, each in report order.
    std::stable_partition(series.begin(), series.end(),
                          [](const Series& s) { return s.scene == "generated"; });
    for (Series& s : series) {
        std::stable_sort(s.points.begin(), s.points.end(),
                         [](const Point& a, const Point& b) { return a.objects < b.objects; });
        bool clashes = std::any_of(series.begin(), series.end(), [&](const Series& other) {
            return &other != &s && other.strategy == s.strategy;
        });
        if (clashes && s.scene == "animometer") {
            s.label = s.scene + " " + s.strategy;
        }
    }
    return series;
}

// Log axes can show only finite positive values; the rest are skipped, not clamped.
bool plottable(double value) {
    return value > 0 && std::isfinite(value);
}

std::optional<Spread> spreadOf(const Point& point, Quantity quantity) {
    switch (quantity) {
        case Quantity::CpuMs:
            return point.cpu;
        case Quantity::GpuMs:
            return point.gpu;
        case Quantity::Triangles:
            return point.triangles;
    }
    return std::nullopt;
}

// Appends SVG elements to one string; every coordinate goes through number().
struct SvgBuilder {
    std::string out;

    void text(double x, double y, std::string_view content, std::string_view attributes = {}) {
        out += "<text x=\"" + number(x) + "\" y=\"" + number(y) + "\" " + std::string(attributes) +
               ">" + escapeXml(content) + "</text>\n";
    }

    void line(double x1, double y1, double x2, double y2, std::string_view attributes) {
        out += "<line x1=\"" + number(x1) + "\" y1=\"" + number(y1) + "\" x2=\"" + number(x2) +
               "\" y2=\"" + number(y2) + "\" " + std::string(attributes) + "/>\n";
    }

    void marker(size_t series, double x, double y, std::string_view tip) {
        const Outline& outline = kMarkers[series % kMarkers.size()];
        const std::string tag = outline.empty() ? "circle" : "polygon";
        out += "<" + tag + " class=\"marker\"";
        if (outline.empty()) {
            out += " cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"3.5\"";
        } else {
            out += " points=\"";
            for (size_t i = 0; i < outline.size(); ++i) {
                out += (i ? " " : "") + number(x + outline[i].first) + "," +
                       number(y + outline[i].second);
            }
            out += "\"";
        }
        // A <title> child is the tooltip browsers show on hover: the numbers behind a point.
        out += "><title>" + escapeXml(tip) + "</title></" + tag + ">\n";
    }

    // Opens a group in the series' colour; lines inside take its dash pattern with dashed().
    void beginSeries(size_t series, std::string_view extra = {}) {
        const std::string colour(kPalette[series % kPalette.size()]);
        out += "<g" + std::string(extra) + " stroke=\"" + colour + "\" fill=\"" + colour + "\">\n";
    }

    static std::string dashed(size_t series) {
        const std::string_view dash = kDashes[series % kDashes.size()];
        return "fill=\"none\" stroke-width=\"1.8\"" +
               (dash.empty() ? "" : " stroke-dasharray=\"" + std::string(dash) + "\"");
    }
};

struct PanelBox {
    double left, right, top, bottom;
};

// The positive medians and whisker ends a panel shows, which set its y range.
std::vector<double> panelValues(const std::vector<Series>& series, Quantity quantity) {
    std::vector<double> values;
    for (const Series& s : series) {
        for (const Point& p : s.points) {
            auto t = spreadOf(p, quantity);
            if (plottable(p.objects) && t && plottable(t->median)) {
                values.push_back(t->median);
                if (plottable(t->high)) {
                    values.push_back(t->high);
                }
            }
        }
    }
    return values;
}

void appendPanel(SvgBuilder& svg,
                 const std::vector<Series>& series,
                 Quantity quantity,
                 std::pair<int, int> xDecades,
                 const PanelBox& box) {
    const std::vector<double> values = panelValues(series, quantity);
    const bool counts = quantity == Quantity::Triangles;
    const auto [yLow, yHigh] = decadeRange(values);
    const LogAxis xAxis{xDecades.first, xDecades.second, box.left, box.right};
    const LogAxis yAxis{yLow, yHigh, box.bottom, box.top};
    const double xMid = (box.left + box.right) / 2;
    const double yMid = (box.top + box.bottom) / 2;

    svg.out += "<g class=\"panel\">\n";
    const char* title = quantity == Quantity::CpuMs ? "CPU time per frame (encode + submit), median"
                        : quantity == Quantity::GpuMs ? "GPU time per frame, median"
                                                      : "Triangles per frame, median";
    svg.text(xMid, box.top - 12, title,
             "text-anchor=\"middle\" font-size=\"13\" font-weight=\"bold\"");
    // Decade gridlines carry the labels; fainter ones at 2..9 make log distances readable.
    for (bool vertical : {true, false}) {
        const LogAxis& axis = vertical ? xAxis : yAxis;
        for (int e = axis.low; e <= axis.high; ++e) {
            for (int m = 1; m <= (e < axis.high ? 9 : 1); ++m) {
                const double p = axis.map(m * std::pow(10.0, e));
                const char* style = m == 1 ? "stroke=\"#c8c8c8\"" : "stroke=\"#eeeeee\"";
                vertical ? svg.line(p, box.top, p, box.bottom, style)
                         : svg.line(box.left, p, box.right, p, style);
            }
            const double p = axis.map(std::pow(10.0, e));
            vertical ? svg.text(p, box.bottom + 15, decadeLabel(e, true), "text-anchor=\"middle\"")
                     : svg.text(box.left - 6, p + 4, decadeLabel(e, counts), "text-anchor=\"end\"");
        }
    }
    svg.out += "<rect x=\"" + number(box.left) + "\" y=\"" + number(box.top) + "\" width=\"" +
               number(box.right - box.left) + "\" height=\"" + number(box.bottom - box.top) +
               "\" fill=\"none\" stroke=\"#444444\"/>\n";
    svg.text(xMid, box.bottom + 32, "objects (crowds: characters; log scale)",
             "text-anchor=\"middle\"");
    svg.text(box.left - 44, yMid,
             counts ? "triangles drawn (else submitted; log scale)" : "milliseconds (log scale)",
             "text-anchor=\"middle\" transform=\"rotate(-90 " + number(box.left - 44) + " " +
                 number(yMid) + ")\"");
    if (values.empty()) {
        svg.text(xMid, yMid, "no data", "text-anchor=\"middle\" fill=\"#888888\"");
    }

    for (size_t i = 0; i < series.size(); ++i) {
        const Series& s = series[i];
        std::string points;
        SvgBuilder marks;
        for (const Point& p : s.points) {
            auto t = spreadOf(p, quantity);
            if (!plottable(p.objects) || !t || !plottable(t->median)) {
                continue;
            }
            const double x = xAxis.map(p.objects);
            const double y = yAxis.map(t->median);
            points += (points.empty() ? "" : " ") + number(x) + "," + number(y);
            const std::string unit = counts ? " triangles" : " ms";
            const int precision = counts ? 0 : 3;
            std::string tip = s.label + ": " + number(p.objects, 0) + " objects, median " +
                              number(t->median, precision) + unit;
            if (plottable(t->high)) {
                const double yP95 = yAxis.map(t->high);
                marks.out += "<path class=\"p95\" fill=\"none\" d=\"M" + number(x) + "," +
                             number(y) + "V" + number(yP95) + "M" + number(x - 3) + "," +
                             number(yP95) + "H" + number(x + 3) + "\"/>\n";
                tip += (counts ? ", max " : ", p95 ") + number(t->high, precision) + unit;
            }
            marks.marker(i, x, y, tip);
        }
        if (!points.empty()) {
            svg.beginSeries(i, " class=\"series\" data-series=\"" + escapeXml(s.label) + "\"");
            svg.out += "<polyline " + SvgBuilder::dashed(i) + " points=\"" + points + "\"/>\n" +
                       marks.out + "</g>\n";
        }
    }
    svg.out += "</g>\n";
}

void appendLegend(SvgBuilder& svg, const std::vector<Series>& series, double width, double top) {
    const double columnWidth = (width - 40) / kLegendColumns;
    svg.out += "<g class=\"legend\">\n";
    for (size_t i = 0; i < series.size(); ++i) {
        const double x = 20 + static_cast<double>(i % kLegendColumns) * columnWidth;
        const double y = top + static_cast<double>(i / kLegendColumns) * kLegendRowHeight + 9;
        svg.beginSeries(i);
        svg.line(x, y, x + 28, y, SvgBuilder::dashed(i));
        svg.marker(i, x + 14, y, series[i].label);
        svg.out += "</g>\n";
        svg.text(x + 34, y + 4, series[i].label);
    }
    svg.out += "</g>\n";
}

std::string stringField(const json& object, const char* key) {
    auto it = object.find(key);
    return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// "encore 0.1.0 · Dawn ... · 60 frames after 10 warm-up": what a reader needs to compare runs.
std::string detailsLine(const json& report, bool anyGpu, bool anyTriangles) {
    std::string line = "encore " + stringField(report, "encore");
    if (auto dawn = stringField(report, "dawn"); !dawn.empty()) {
        line += " \xC2\xB7 Dawn " + dawn;
    }
    if (report.contains("frames") && report["frames"].is_number_integer()) {
        line += " \xC2\xB7 " + report["frames"].dump() + " frames";
        if (report.contains("warmup") && report["warmup"].is_number_integer()) {
            line += " after " + report["warmup"].dump() + " warm-up";
        }
    }
    return line + (anyGpu ? "" : " \xC2\xB7 no GPU timestamps") +
           " \xC2\xB7 whiskers: median to p95" + (anyTriangles ? " (triangles: to max)" : "");
}

}  // namespace

Result<json> mergeReports(const std::vector<NamedReport>& reports) {
    if (reports.empty()) {
        return makeError(ErrorCode::InvalidFormat, "No benchmark report to merge.");
    }
    json merged;
    for (const NamedReport& named : reports) {
        const json& report = named.report;
        if (!report.is_object() || !report.contains("results") || !report["results"].is_array()) {
            return makeError(ErrorCode::InvalidFormat,
                             named.name + ": the benchmark report has no \"results\" array.");
        }
        if (merged.is_null()) {
            merged = report;
            continue;
        }
        // Timings of different adapters (or drivers) do not belong on one curve.
        const json none;
        const json& first = merged.contains("adapter") ? merged["adapter"] : none;
        const json& adapter = report.contains("adapter") ? report["adapter"] : none;
        if (adapter != first) {
            return makeError(ErrorCode::InvalidFormat,
                             named.name + ": the adapter (" + adapter.dump() +
                                 ") differs from that of " + reports.front().name + " (" +
                                 first.dump() + "); plot reports of one adapter together.");
        }
        for (const json& result : report["results"]) {
            merged["results"].push_back(result);
        }
    }
    return merged;
}

Result<std::string> plotScalingSvg(const json& report) {
    if (!report.is_object() || !report.contains("results") || !report["results"].is_array()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The benchmark report has no \"results\" array.");
    }
    const json* adapter = report.contains("adapter") ? &report["adapter"] : nullptr;
    if (!adapter || !adapter->is_object() || stringField(*adapter, "name").empty()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The benchmark report has no \"adapter.name\" string.");
    }
    auto read = readSeries(report["results"]);
    if (!read) {
        return read.error();
    }
    const std::vector<Series>& series = *read;
    if (series.empty()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The benchmark report has no \"generated\", \"animometer\", \"crowd\", "
                         "\"flythrough\" or \"city\" results to plot (" +
                             std::to_string(report["results"].size()) + " results).");
    }

    std::vector<double> objects;
    bool anyGpu = false;
    bool anyTriangles = false;
    for (const Series& s : series) {
        for (const Point& p : s.points) {
            if (plottable(p.objects)) {
                objects.push_back(p.objects);
            }
            anyGpu = anyGpu || p.gpu.has_value();
            anyTriangles = anyTriangles || p.triangles.has_value();
        }
    }
    std::vector<Quantity> quantities = {Quantity::CpuMs};
    if (anyGpu) {
        quantities.push_back(Quantity::GpuMs);
    }
    if (anyTriangles) {
        quantities.push_back(Quantity::Triangles);
    }
    const double width = quantities.size() > 2 ? kWideWidth : kWidth;

    const size_t legendRows = (series.size() + kLegendColumns - 1) / kLegendColumns;
    const double legendHeight = static_cast<double>(legendRows) * kLegendRowHeight;
    // The plot keeps a readable height; only an unusually long legend makes the image taller.
    const double height = std::max(kMinHeight, kPlotTop + kMinPlotHeight + 56 + legendHeight);
    const double legendTop = height - 12 - legendHeight;

    std::string title = "Encore benchmark: " + stringField(*adapter, "name");
    if (auto backend = stringField(*adapter, "backend"); !backend.empty()) {
        title += " (" + backend + ")";
    }
    if (auto date = stringField(report, "date"); !date.empty()) {
        title += ", " + date;
    }

    SvgBuilder svg;
    const std::string widthText = number(width, 0);
    svg.out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + widthText + "\" height=\"" +
               number(height, 0) + "\" viewBox=\"0 0 " + widthText + " " + number(height, 0) +
               "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    svg.out += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    svg.text(width / 2, 24, title, "text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\"");
    svg.text(width / 2, 42, detailsLine(report, anyGpu, anyTriangles),
             "text-anchor=\"middle\" fill=\"#555555\"");

    const double panelWidth = (width - 20) / static_cast<double>(quantities.size());
    for (size_t i = 0; i < quantities.size(); ++i) {
        const double left = 10 + panelWidth * static_cast<double>(i);
        appendPanel(svg, series, quantities[i], decadeRange(objects),
                    {left + 64, left + panelWidth - 18, kPlotTop, legendTop - 44});
    }
    appendLegend(svg, series, width, legendTop);
    svg.out += "</svg>\n";
    return std::move(svg.out);
}

}  // namespace encore::app
