#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Commands.h"
#include "CullingFlags.h"
#include "StrategyOptions.h"
#include "bench/Benchmark.h"
#include "core/Elapsed.h"
#include "core/FileIO.h"

namespace encore::app {

namespace {

struct BenchCommandOptions {
    bench::BenchOptions bench;
    std::vector<std::string> strategies;
    bool bundle = false;  // Each strategy also recorded once into render bundles.
    std::string json;
    std::string markdown;
    std::string plot;
    bool smoke = false;
    std::vector<std::string> animate;
    std::vector<std::string> scenes;
};

Result<void> writeText(const std::string& path, const std::string& text) {
    return writeFile(path,
                     std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

int runBench(BenchCommandOptions options, const GlobalOptions& global) {
    auto strategies = parseStrategySelection(options.strategies, options.bundle);
    if (!strategies) {
        return reportError(strategies.error());
    }
    options.bench.strategies = std::move(*strategies);
    options.bench.allowUrisOutside = global.allowUrisOutside;
    if (options.smoke) {
        // A quick run that keeps the benchmark code path exercised in CI.
        options.bench.objectCounts = {100, 1000};
        options.bench.frames = 3;
        options.bench.warmup = 1;
        options.bench.width = options.bench.height = 128;
    }
    for (const auto& name : options.scenes) {
        options.bench.scenes.push_back(*bench::generatedSceneFromName(name));
    }
    for (const auto& name : options.animate) {
        options.bench.animate.push_back(*render::animationEvaluationFromName(name));
    }
    if (options.bench.objectCounts.empty() && options.bench.models.empty() &&
        options.bench.animometerTriangles.empty() && options.bench.crowdCharacters.empty()) {
        options.bench.objectCounts = {1000, 10000};
    }

    auto context = createContext(global, /*timestamps=*/!options.bench.callgrind);
    if (!context) {
        return reportError(context.error());
    }
    if (!global.verbose) {
        // Every benchmark names its adapter; --verbose already printed it.
        std::fprintf(stderr, "adapter: %s\n", context->adapterDescription().summary().c_str());
    }
    const auto start = std::chrono::steady_clock::now();
    auto report = bench::runBenchmarks(*context, options.bench, [&](const std::string& label) {
        injectFaultsForTests(*context);
        if (global.verbose) {
            const double elapsed = secondsSince(start);
            std::fprintf(stderr, "[%7.1f s] measuring %s\n", elapsed, label.c_str());
        }
    });
    if (!report) {
        return reportError(report.error());
    }
    const std::string markdown = bench::toMarkdown(*report);
    std::printf("%s", markdown.c_str());
    if (!options.markdown.empty()) {
        if (auto written = writeText(options.markdown, markdown); !written) {
            return reportError(written.error());
        }
    }
    const auto json = bench::toJson(*report);
    if (!options.json.empty()) {
        if (auto written = writeText(options.json, json.dump(2) + "\n"); !written) {
            return reportError(written.error());
        }
    }
    if (!options.plot.empty()) {
        if (int code = writePlot(json, options.plot); code != kExitOk) {
            return code;
        }
    }
    return kExitOk;
}

}  // namespace

void addBenchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<BenchCommandOptions>();
    auto& bench = options->bench;
    auto* command = app.add_subcommand(
        "bench",
        "Measure strategies on generated scenes, glTF models and the Animometer scene: CPU encode "
        "and submit time, GPU time (timestamp queries), API call counts; median and p95.");
    command
        ->add_option("--objects", bench.objectCounts,
                     "Generated scenes with these object counts (default 1000 10000)")
        ->delimiter(',');
    command
        ->add_option("--scene", options->scenes,
                     "What the generated scenes (--objects) are: grid (seen whole, still; the "
                     "default), flythrough (a camera flying through a lattice of objects) or "
                     "city (a camera driving down the streets of a city); several measure each")
        ->delimiter(',')
        ->check(CLI::IsMember({"grid", "flythrough", "city"}));
    command->add_option("--path-step", bench.pathStep,
                        "Units the flythrough and city cameras move per frame (default 0: once "
                        "round their loop over the measured frames)");
    command->add_option("--model", bench.models, "glTF models to measure (repeatable)");
    command
        ->add_option("--animometer", bench.animometerTriangles,
                     "Animometer scenes with these triangle counts")
        ->delimiter(',');
    command
        ->add_option("--crowd", bench.crowdCharacters,
                     "Animated crowds (encore gen --crowd) with these character counts, "
                     "animated on the cpu and on the gpu unless --animate says")
        ->delimiter(',');
    command
        ->add_option("--animate", options->animate,
                     "Animate models and crowds every frame, evaluated on the cpu, the gpu or "
                     "both (cpu,gpu), each measured separately")
        ->delimiter(',')
        ->check(CLI::IsMember({"cpu", "gpu"}));
    command->add_option("-s,--strategy", options->strategies,
                        "Only these strategies (repeatable; default: all; a direct one with "
                        "+bundle, e.g. naive+bundle, is recorded once into a render bundle)");
    command->add_flag("--bundle", options->bundle,
                      "Also measure each strategy recorded once into render bundles (materials "
                      "and gpu-culling as bundles and gpu-culling-bundles, the others as "
                      "NAME+bundle): the bundling axis");
    command->add_option("--frames", bench.frames, "Measured frames")->capture_default_str();
    command->add_option("--warmup", bench.warmup, "Warm-up frames")->capture_default_str();
    command
        ->add_option("--warmup-time", bench.warmupSeconds,
                     "Seconds the warm-up lasts at least, repeating its last frame (default: "
                     "0.5 on a GPU, which raises its clocks only under load; 0 on a CPU "
                     "adapter; none with --warmup 0)")
        ->check(CLI::Range(0.0, 600.0));
    command->add_option("--width", bench.width, "Target width")->capture_default_str();
    command->add_option("--height", bench.height, "Target height")->capture_default_str();
    command->add_option("--samples", bench.samples, "Multisampling: 1 or 4")
        ->check(CLI::IsMember({1, 4}))
        ->capture_default_str();
    command->add_option("--meshes", bench.meshes, "Distinct meshes of generated scenes")
        ->capture_default_str();
    command->add_option("--materials", bench.materials, "Materials of generated scenes")
        ->capture_default_str();
    command
        ->add_option("--tessellation", bench.tessellation, "Segments of the generated round shapes")
        ->capture_default_str();
    command->add_flag("--textures,!--no-textures", bench.textures,
                      "Every other material of the generated scenes samples base colour and "
                      "metallic-roughness textures (default: on)");
    command->add_option("--json", options->json, "Write the report as JSON");
    command->add_option("--markdown", options->markdown, "Write the report as Markdown");
    command->add_option("--plot", options->plot, "Write the scaling curves as SVG");
    command->add_flag("--callgrind", bench.callgrind,
                      "No warm-up or GPU timer; bracket the measured frames for valgrind "
                      "--tool=callgrind --instr-atstart=no");
    command->add_flag("--gpu-timer,!--no-gpu-timer", bench.gpuTimer,
                      "Timestamp queries around every pass (default: on); without them GPU "
                      "time is n/a and the CPU frame is what an application pays");
    command->add_flag("--gpu-steps", bench.gpuSteps,
                      "Time each step of a pass of several (the visibility strategy's culling, "
                      "rasters, pyramid, binning, shading) as a pass of its own, to see where "
                      "the time goes; the boundaries add to the frame's GPU time");
    command
        ->add_option("--gpu-wait", bench.gpuWait,
                     "How the CPU waits for the GPU after each frame: spin (the core stays "
                     "awake; default) or block (it may sleep, and wake slower); --callgrind "
                     "always blocks")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, gpu::WaitMode>{{"spin", gpu::WaitMode::Spin},
                                                 {"block", gpu::WaitMode::Block}},
            CLI::ignore_case));
    command->add_flag("--smoke", options->smoke, "A few frames of small scenes (CI)");
    addCullingOptions(*command, bench.culling);
    command->add_flag(
        "--frustum-baseline", bench.frustumBaseline,
        "Also measure each gpu-culling and the visibility strategy with frustum culling "
        "alone (no occlusion culling, no levels of detail), in the same run");
    command->callback([options, &global, &exitCode] { exitCode = runBench(*options, global); });
}

}  // namespace encore::app
