#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "bench/Benchmark.h"

namespace encore::bench {

namespace {

// The time the warm-up lasted at least (none without warm-up frames).
double warmupSeconds(const BenchOptions& options) {
    return options.callgrind || options.warmup == 0 ? 0.0 : options.warmupSeconds.value_or(0.0);
}

nlohmann::json percentilesJson(const render::Percentiles& p) {
    return {{"median", p.median}, {"p95", p.p95}};
}

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof(text), pattern, value);
    return text;
}

std::string milliseconds(const render::Percentiles& p) {
    return format("%.3f", p.median) + " (" + format("%.3f", p.p95) + ")";
}

// Per-frame counts as "median (min-max)"; "-" when there are none.
std::string countRange(std::vector<std::uint64_t> counts) {
    if (counts.empty()) {
        return "-";
    }
    std::sort(counts.begin(), counts.end());
    const std::string range =
        " (" + std::to_string(counts.front()) + "–" + std::to_string(counts.back()) + ")";
    return std::to_string(counts[counts.size() / 2]) +
           (counts.front() == counts.back() ? std::string() : range);
}

nlohmann::json countsJson(const std::vector<std::uint64_t>& counts) {
    return counts.empty() ? nlohmann::json(nullptr) : nlohmann::json(counts);
}

}  // namespace

nlohmann::json toJson(const render::DrawCounters& c) {
    return {{"setPipeline", c.setPipeline},
            {"setBindGroup", c.setBindGroup},
            {"setVertexBuffer", c.setVertexBuffer},
            {"setIndexBuffer", c.setIndexBuffer},
            {"draw", c.draw},
            {"drawIndexed", c.drawIndexed},
            {"drawIndirect", c.drawIndirect},
            {"executeBundles", c.executeBundles},
            {"primitives", c.primitives},
            {"instances", c.instances},
            {"triangles", c.triangles},
            {"apiCalls", c.apiCalls()}};
}

nlohmann::json toJson(const BenchReport& report) {
    const auto& a = report.adapter;
    nlohmann::json json = {
        {"encore", "0.1.0"},
        {"date", report.date},
        {"adapter",
         {{"name", a.name},
          {"backend", gpu::backendName(a.backend)},
          {"driver", a.driver},
          {"vendor", a.vendor},
          {"summary", a.summary()}}},
        {"dawn", report.dawnVersion},
        {"host", {{"cpu", report.cpu}, {"cores", report.cores}}},
        {"frames", report.options.frames},
        {"warmup", report.options.callgrind ? 0 : report.options.warmup},
        {"warmupSeconds", warmupSeconds(report.options)},
        {"callgrind", report.options.callgrind},
        {"generated",
         {{"meshes", report.options.meshes},
          {"materials", report.options.materials},
          {"tessellation", report.options.tessellation},
          {"textures", report.options.textures},
          {"pathStep", report.options.pathStep},
          {"scenes",
           [&] {
               nlohmann::json scenes = nlohmann::json::array();
               for (const GeneratedScene scene : report.options.scenes) {
                   scenes.push_back(std::string(generatedSceneName(scene)));
               }
               return scenes.empty() ? nlohmann::json::array({"grid"}) : scenes;
           }()}}},
        {"culling",
         {{"occlusion", report.options.culling.occlusion},
          {"levelsOfDetail", report.options.culling.levelsOfDetail},
          {"lodErrorPixels", report.options.culling.lodErrorPixels},
          {"computeRasterPixels", report.options.culling.computeRasterPixels},
          {"workgroupRasterPixels", report.options.culling.workgroupRasterPixels}}},
        {"gpuWait", report.options.gpuWait == gpu::WaitMode::Spin && !report.options.callgrind
                        ? "spin"
                        : "block"},
        {"timestamps", report.timestamps},
        {"gpuSteps", report.timestamps && report.options.gpuSteps},
        {"environmentMilliseconds", report.environmentMilliseconds},
        {"target",
         {{"width", report.options.width},
          {"height", report.options.height},
          {"samples", report.options.samples}}},
        {"results", nlohmann::json::array()},
        {"skipped", report.skipped},
    };
    for (const BenchResult& result : report.results) {
        json["results"].push_back({
            {"scene", result.scene},
            {"label", result.label},
            {"objects", result.objects},
            {"strategy", result.strategy},
            {"animation", result.animation},
            {"animationMs",
             result.animationCpu ? percentilesJson(*result.animationCpu) : nlohmann::json(nullptr)},
            {"animationWork",
             result.animation.empty()
                 ? nlohmann::json(nullptr)
                 : nlohmann::json{{"channelsEvaluated",
                                   result.animationWork.player.channelsEvaluated},
                                  {"jointsUpdated", result.animationWork.player.jointsUpdated},
                                  {"instancesWritten", result.animationWork.instancesWritten},
                                  {"jointsWritten", result.animationWork.upload.jointsWritten},
                                  {"weightsWritten", result.animationWork.upload.weightsWritten},
                                  {"gpuDispatches", result.animationWork.gpu.dispatches},
                                  {"gpuCopies", result.animationWork.gpu.copies},
                                  {"bytesWritten", result.animationWork.bytesWritten}}},
            {"encodeMs", percentilesJson(result.encode)},
            {"submitMs", percentilesJson(result.submit)},
            {"cpuMs", percentilesJson(result.cpu)},
            {"warmupFrames", result.warmupFrames},
            {"gpuMs", result.gpu ? percentilesJson(*result.gpu) : nlohmann::json(nullptr)},
            {"gpuSpanMs",
             result.gpuSpan ? percentilesJson(*result.gpuSpan) : nlohmann::json(nullptr)},
            {"frame", toJson(result.frame)},
            {"bundleContents", toJson(result.bundleContents)},
            {"trianglesSubmitted", countsJson(result.trianglesSubmitted)},
            {"trianglesDrawn", countsJson(result.trianglesDrawn)},
            {"trianglesCompute", countsJson(result.trianglesCompute)},
            {"gpuPassesMs",
             [&] {
                 nlohmann::json passes = nlohmann::json::object();
                 for (const auto& [label, times] : result.gpuPasses) {
                     passes[label] = percentilesJson(times);
                 }
                 return passes;
             }()},
        });
    }
    return json;
}

namespace {

// The run's settings: adapter, frames, target, scenes and culling options.
void writeMarkdownHeader(std::ostringstream& out, const BenchReport& report) {
    out << "Date: " << report.date << "  \n"
        << "Adapter: " << report.adapter.summary() << "  \n"
        << "Dawn: " << report.dawnVersion << "  \n"
        << "Host CPU: " << report.cpu << " (" << report.cores << " threads)  \n"
        << "Frames: " << report.options.frames << " measured after "
        << (report.options.callgrind ? 0 : report.options.warmup) << " warm-up (at least "
        << warmupSeconds(report.options) << " s), " << report.options.width << "x"
        << report.options.height << " target (" << report.options.samples
        << (report.options.samples == 1 ? " sample" : " samples") << " per pixel); the CPU "
        << (report.options.gpuWait == gpu::WaitMode::Spin && !report.options.callgrind ? "spins"
                                                                                       : "blocks")
        << " while it waits for the GPU after each frame; GPU time from timestamp queries: "
        << (report.timestamps ? (report.options.gpuSteps ? "yes, each step a pass of its own"
                                                         : "yes, passes as the frame runs them")
                              : "n/a")
        << "  \n"
        << "Image-based lighting maps built in " << report.environmentMilliseconds
        << " ms (default studio environment)  \n"
        << "Generated scenes: " << report.options.meshes << " meshes, " << report.options.materials
        << " materials"
        << (report.options.textures ? " (every other one textured)" : " (texture-less)")
        << ", tessellation " << report.options.tessellation << "; gpu-culling: occlusion culling "
        << (report.options.culling.occlusion ? "on" : "off") << ", levels of detail "
        << (report.options.culling.levelsOfDetail
                ? "under " + format("%g", report.options.culling.lodErrorPixels) + " pixel(s)"
                : std::string("off"))
        << "; visibility: compute raster up to "
        << format("%g", report.options.culling.computeRasterPixels) << " pixels per thread, "
        << format("%g", report.options.culling.workgroupRasterPixels) << " per workgroup"
        << (report.options.pathStep > 0.0f
                ? "; flythrough and city cameras move " + format("%g", report.options.pathStep) +
                      " units per frame"
                : std::string("; flythrough and city cameras go once round their loops over the "
                              "measured frames"))
        << "\n\n"
        << "Times in milliseconds per frame, median (p95). CPU = encode + submit; \"vs naive\" "
           "is naive's CPU median divided by the strategy's, in the same scene. Triangles per "
           "frame, median (min–max): submitted = what the recorded draws could draw, drawn = "
           "what GPU culling let through (- for strategies without it: they draw what they "
           "submit).\n";
}

// One scene's table: a row per strategy.
void writeSceneTable(std::ostringstream& out,
                     const std::string& label,
                     const std::vector<const BenchResult*>& results) {
    double naive = 0.0;
    for (const BenchResult* result : results) {
        if (result->strategy == "naive") {
            naive = result->cpu.median;
        }
    }
    const bool animated = results.front()->animationCpu.has_value();
    const bool triangles = !results.front()->trianglesSubmitted.empty();
    bool computeRaster = false;
    for (const BenchResult* result : results) {
        computeRaster = computeRaster || !result->trianglesCompute.empty();
    }
    out << "\n### " << label << " (" << results.front()->objects << " objects)\n\n"
        << "| strategy | CPU frame | encode | submit | GPU | vs naive | API calls | draws | "
           "bundle draws |"
        << (triangles ? " triangles submitted | triangles drawn |" : "")
        << (triangles && computeRaster ? " of them in compute |" : "")
        << (animated ? " animation (share of CPU frame) | bytes written |" : "")
        << "\n|---|---:|---:|---:|---:|---:|---:|---:|---:|" << (triangles ? "---:|---:|" : "")
        << (triangles && computeRaster ? "---:|" : "") << (animated ? "---:|---:|" : "") << "\n";
    for (const BenchResult* result : results) {
        out << "| " << result->strategy << " | " << milliseconds(result->cpu) << " | "
            << milliseconds(result->encode) << " | " << milliseconds(result->submit) << " | "
            << (result->gpu ? milliseconds(*result->gpu) : std::string("n/a")) << " | "
            << (naive > 0.0 && result->cpu.median > 0.0
                    ? format("%.1fx", naive / result->cpu.median)
                    : std::string("-"))
            << " | " << result->frame.apiCalls() << " | " << result->frame.drawCalls() << " | "
            << result->bundleContents.drawCalls() << " |";
        if (triangles) {
            out << " " << countRange(result->trianglesSubmitted) << " | "
                << countRange(result->trianglesDrawn) << " |";
            if (computeRaster) {
                out << " " << countRange(result->trianglesCompute) << " |";
            }
        }
        if (animated && result->animationCpu) {
            const double share = result->cpu.median > 0.0
                                     ? 100.0 * result->animationCpu->median / result->cpu.median
                                     : 0.0;
            out << " " << milliseconds(*result->animationCpu) << " (" << format("%.0f%%", share)
                << ") | " << result->animationWork.bytesWritten << " |";
        }
        out << "\n";
    }
}

// Where the GPU time of strategies with more than one kind of pass goes.
void writeGpuPasses(std::ostringstream& out, const std::vector<const BenchResult*>& results) {
    bool passes = false;
    for (const BenchResult* result : results) {
        passes = passes || result->gpuPasses.size() > 1;
    }
    if (passes) {
        out << "\nGPU time per pass, median (p95):\n\n";
        for (const BenchResult* result : results) {
            if (result->gpuPasses.size() <= 1) {
                continue;
            }
            out << "- " << result->strategy << ":";
            const char* separator = " ";
            for (const auto& [passLabel, times] : result->gpuPasses) {
                out << separator << passLabel << " " << milliseconds(times);
                separator = ", ";
            }
            out << "\n";
        }
    }
}

}  // namespace

std::string toMarkdown(const BenchReport& report) {
    std::ostringstream out;
    writeMarkdownHeader(out, report);

    // Results grouped by scene label, in report order.
    std::vector<std::string> labels;
    std::map<std::string, std::vector<const BenchResult*>> byLabel;
    for (const BenchResult& result : report.results) {
        if (!byLabel.contains(result.label)) {
            labels.push_back(result.label);
        }
        byLabel[result.label].push_back(&result);
    }
    for (const auto& label : labels) {
        writeSceneTable(out, label, byLabel[label]);
        writeGpuPasses(out, byLabel[label]);
    }
    if (!report.skipped.empty()) {
        out << "\nNot measured on this adapter:\n\n";
        for (const auto& skipped : report.skipped) {
            out << "- " << skipped << "\n";
        }
    }
    return out.str();
}

}  // namespace encore::bench
