#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "Commands.h"
#include "bench/BenchmarkReportReader.h"
#include "bench/PlotWriter.h"
#include "core/FileIO.h"

namespace encore::app {

namespace {

std::string shellQuote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

// A PNG beside the SVG when Debian's rsvg-convert (librsvg2-bin) is installed; optional.
void convertToPng(const std::string& svgPath) {
    if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) {
        return;
    }
    std::string pngPath = svgPath;
    if (pngPath.size() > 4 && pngPath.substr(pngPath.size() - 4) == ".svg") {
        pngPath.resize(pngPath.size() - 4);
    }
    pngPath += ".png";
    const std::string command =
        "rsvg-convert -o " + shellQuote(pngPath) + " " + shellQuote(svgPath);
    if (std::system(command.c_str()) == 0) {
        std::fprintf(stderr, "plot: %s\n", pngPath.c_str());
    }
}

}  // namespace

int writePlot(const nlohmann::json& report, const std::string& path) {
    auto svg = bench::plotScalingSvg(report);
    if (!svg) {
        return reportError(svg.error());
    }
    auto written =
        writeFile(path, std::span(reinterpret_cast<const std::uint8_t*>(svg->data()), svg->size()));
    if (!written) {
        return reportError(written.error());
    }
    std::fprintf(stderr, "plot: %s\n", path.c_str());
    convertToPng(path);
    return kExitOk;
}

void addPlotCommand(CLI::App& app, const GlobalOptions&, int& exitCode) {
    auto inputs = std::make_shared<std::vector<std::string>>();
    auto output = std::make_shared<std::string>("bench.svg");
    auto* command = app.add_subcommand(
        "plot",
        "Draw the scaling curves of benchmark reports (JSON) as an SVG (and a PNG when "
        "rsvg-convert is installed). Several reports of one adapter are plotted together.");
    command->add_option("reports", *inputs, "Reports written by encore bench --json")->required();
    command->add_option("-o,--output", *output, "The SVG to write")->capture_default_str();
    command->callback([inputs, output, &exitCode] {
        std::vector<bench::NamedReport> reports;
        for (const std::string& input : *inputs) {
            auto bytes = readFile(input);
            if (!bytes) {
                exitCode = reportError(bytes.error());
                return;
            }
            auto report = nlohmann::json::parse(bytes->begin(), bytes->end(), nullptr, false);
            if (report.is_discarded()) {
                exitCode = reportError(
                    makeError(ErrorCode::InvalidFormat, input + ": the report is not valid JSON."));
                return;
            }
            reports.push_back({input, std::move(report)});
        }
        auto merged = bench::mergeReports(reports);
        if (!merged) {
            exitCode = reportError(merged.error());
            return;
        }
        exitCode = writePlot(*merged, *output);
    });
}

}  // namespace encore::app
