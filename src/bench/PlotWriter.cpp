#include "bench/PlotWriter.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "bench/BenchmarkReportReader.h"
#include "bench/SvgBuilder.h"

namespace encore::bench {
namespace {

using bench::ScalingPoint;
using bench::ScalingSeries;
using bench::Spread;
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

// Marker outlines (an empty one is a circle): six shapes against four dash patterns give twelve
// series that differ in greyscale.
const std::array<Outline, 6> kMarkers = {
    Outline{},
    Outline{{-3.2, -3.2}, {3.2, -3.2}, {3.2, 3.2}, {-3.2, 3.2}},
    Outline{{0, -4.5}, {4.2, 3.2}, {-4.2, 3.2}},
    Outline{{0, -4.5}, {4.5, 0}, {0, 4.5}, {-4.5, 0}},
    Outline{{0, 4.5}, {4.2, -3.2}, {-4.2, -3.2}},
    Outline{{-4.2, -4.2}, {4.2, 4.2}, {4.2, -4.2}, {-4.2, 4.2}}};  // A bow tie.

// What a panel's y axis shows.
enum class Quantity {
    CpuMs,
    GpuMs,
    Triangles,
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

// Log axes can show only finite positive values; the rest are skipped, not clamped.
bool plottable(double value) {
    return value > 0 && std::isfinite(value);
}

std::optional<Spread> spreadOf(const ScalingPoint& point, Quantity quantity) {
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

// Opens a group in the series' colour; lines inside take its dash pattern with dashed().
void beginSeries(SvgBuilder& svg, size_t series, std::string_view extra = {}) {
    svg.beginGroup(kPalette[series % kPalette.size()], extra);
}

// The attributes of a series' line: unfilled, in its dash pattern.
std::string dashed(size_t series) {
    const std::string_view dash = kDashes[series % kDashes.size()];
    return "fill=\"none\" stroke-width=\"1.8\"" +
           (dash.empty() ? "" : " stroke-dasharray=\"" + std::string(dash) + "\"");
}

void seriesMarker(SvgBuilder& svg, size_t series, double x, double y, std::string_view tip) {
    svg.marker(kMarkers[series % kMarkers.size()], x, y, tip);
}

struct PanelBox {
    double left, right, top, bottom;
};

// The positive medians and whisker ends a panel shows, which set its y range.
std::vector<double> panelValues(const std::vector<ScalingSeries>& series, Quantity quantity) {
    std::vector<double> values;
    for (const ScalingSeries& s : series) {
        for (const ScalingPoint& p : s.points) {
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
                 const std::vector<ScalingSeries>& series,
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
    svg.out += "<rect x=\"" + svgNumber(box.left) + "\" y=\"" + svgNumber(box.top) + "\" width=\"" +
               svgNumber(box.right - box.left) + "\" height=\"" + svgNumber(box.bottom - box.top) +
               "\" fill=\"none\" stroke=\"#444444\"/>\n";
    svg.text(xMid, box.bottom + 32, "objects (crowds: characters; log scale)",
             "text-anchor=\"middle\"");
    svg.text(box.left - 44, yMid,
             counts ? "triangles drawn (else submitted; log scale)" : "milliseconds (log scale)",
             "text-anchor=\"middle\" transform=\"rotate(-90 " + svgNumber(box.left - 44) + " " +
                 svgNumber(yMid) + ")\"");
    if (values.empty()) {
        svg.text(xMid, yMid, "no data", "text-anchor=\"middle\" fill=\"#888888\"");
    }

    for (size_t i = 0; i < series.size(); ++i) {
        const ScalingSeries& s = series[i];
        std::string points;
        SvgBuilder marks;
        for (const ScalingPoint& p : s.points) {
            auto t = spreadOf(p, quantity);
            if (!plottable(p.objects) || !t || !plottable(t->median)) {
                continue;
            }
            const double x = xAxis.map(p.objects);
            const double y = yAxis.map(t->median);
            points += (points.empty() ? "" : " ") + svgNumber(x) + "," + svgNumber(y);
            const std::string unit = counts ? " triangles" : " ms";
            const int precision = counts ? 0 : 3;
            std::string tip = s.label + ": " + svgNumber(p.objects, 0) + " objects, median " +
                              svgNumber(t->median, precision) + unit;
            if (plottable(t->high)) {
                const double yP95 = yAxis.map(t->high);
                marks.out += "<path class=\"p95\" fill=\"none\" d=\"M" + svgNumber(x) + "," +
                             svgNumber(y) + "V" + svgNumber(yP95) + "M" + svgNumber(x - 3) + "," +
                             svgNumber(yP95) + "H" + svgNumber(x + 3) + "\"/>\n";
                tip += (counts ? ", max " : ", p95 ") + svgNumber(t->high, precision) + unit;
            }
            seriesMarker(marks, i, x, y, tip);
        }
        if (!points.empty()) {
            beginSeries(svg, i, " class=\"series\" data-series=\"" + escapeXml(s.label) + "\"");
            svg.out +=
                "<polyline " + dashed(i) + " points=\"" + points + "\"/>\n" + marks.out + "</g>\n";
        }
    }
    svg.out += "</g>\n";
}

void appendLegend(SvgBuilder& svg,
                  const std::vector<ScalingSeries>& series,
                  double width,
                  double top) {
    const double columnWidth = (width - 40) / kLegendColumns;
    svg.out += "<g class=\"legend\">\n";
    for (size_t i = 0; i < series.size(); ++i) {
        const double x = 20 + static_cast<double>(i % kLegendColumns) * columnWidth;
        const double y = top + static_cast<double>(i / kLegendColumns) * kLegendRowHeight + 9;
        beginSeries(svg, i);
        svg.line(x, y, x + 28, y, dashed(i));
        seriesMarker(svg, i, x + 14, y, series[i].label);
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
    ENCORE_TRY_ASSIGN(const std::vector<ScalingSeries> series,
                      bench::readScalingSeries(report["results"]));
    if (series.empty()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The benchmark report has no \"generated\", \"animometer\", \"crowd\", "
                         "\"flythrough\" or \"city\" results to plot (" +
                             std::to_string(report["results"].size()) + " results).");
    }

    std::vector<double> objects;
    bool anyGpu = false;
    bool anyTriangles = false;
    for (const ScalingSeries& s : series) {
        for (const ScalingPoint& p : s.points) {
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
    const std::string widthText = svgNumber(width, 0);
    svg.out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + widthText + "\" height=\"" +
               svgNumber(height, 0) + "\" viewBox=\"0 0 " + widthText + " " + svgNumber(height, 0) +
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

}  // namespace encore::bench
