#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "Commands.h"
#include "StrategyOptions.h"
#include "bench/Benchmark.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"

namespace encore::app {

namespace {

struct StatsOptions {
    std::string model;
    std::vector<std::string> strategies;
    bool bundle = false;  // Each strategy also recorded once into render bundles.
    bool json = false;
    std::uint32_t width = 640;
    std::uint32_t height = 480;
    std::optional<double> time;   // Animate: the frame from time - 1/60 to time.
    std::string animate = "cpu";  // --animate cpu|gpu.
};

struct StrategyStats {
    std::string name;
    std::uint64_t pipelinesCreated = 0;
    render::DrawCounters counters;
    render::DrawCounters bundleContents;  // Zero unless the strategy replays bundles.
    std::uint64_t bundlesRecorded = 0;
    double encodeMilliseconds = 0.0;
    std::optional<render::AnimationFrameStats> animation;
    // What the GPU decided to draw (GPU culling, the visibility buffer), by rasteriser.
    std::optional<render::DrawnTriangles> gpuDrawn;
};

nlohmann::json toJson(const render::AnimationFrameStats& a) {
    if (a.evaluation == render::AnimationEvaluation::Gpu) {
        return {{"evaluation", "gpu"},
                {"computeDispatches", a.gpu.dispatches},
                {"bufferCopies", a.gpu.copies},
                {"animatedNodes", a.gpu.animatedNodes},
                {"worldNodes", a.gpu.worldNodes},
                {"hierarchyLevels", a.gpu.levels},
                {"instances", a.gpu.instances},
                {"joints", a.gpu.joints},
                {"bytesWritten", a.bytesWritten}};
    }
    return {{"evaluation", "cpu"},
            {"channelsEvaluated", a.player.channelsEvaluated},
            {"nodesChanged", a.player.nodesChanged},
            {"worldsUpdated", a.player.worldsUpdated},
            {"jointsUpdated", a.player.jointsUpdated},
            {"instancesWritten", a.instancesWritten},
            {"jointsWritten", a.upload.jointsWritten},
            {"morphWeightsWritten", a.upload.weightsWritten},
            {"bytesWritten", a.bytesWritten}};
}

nlohmann::json toJson(const StrategyStats& stats) {
    nlohmann::json json = {{"strategy", stats.name},
                           {"pipelinesCreated", stats.pipelinesCreated},
                           {"frame", bench::toJson(stats.counters)},
                           {"bundleContents", bench::toJson(stats.bundleContents)},
                           {"bundlesRecorded", stats.bundlesRecorded},
                           {"encodeMilliseconds", stats.encodeMilliseconds}};
    if (stats.animation) {
        json["animation"] = toJson(*stats.animation);
    }
    if (stats.gpuDrawn) {
        json["gpuTriangles"] = {{"hardware", stats.gpuDrawn->hardware},
                                {"compute", stats.gpuDrawn->compute}};
    }
    return json;
}

void printMarkdown(const std::string& model,
                   const std::string& adapter,
                   const std::vector<StrategyStats>& rows) {
    std::printf("Model: %s  \nAdapter: %s\n\n", model.c_str(), adapter.c_str());
    std::printf(
        "| strategy | pipelines created | setPipeline | setBindGroup | setVertexBuffer | "
        "setIndexBuffer | draw | drawIndexed | indirect draws | executeBundles | instances | "
        "triangles |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    auto printRow = [](const std::string& name, std::uint64_t pipelines,
                       const render::DrawCounters& c) {
        std::printf(
            "| %s | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | "
            "%llu |\n",
            name.c_str(), (unsigned long long)pipelines, (unsigned long long)c.setPipeline,
            (unsigned long long)c.setBindGroup, (unsigned long long)c.setVertexBuffer,
            (unsigned long long)c.setIndexBuffer, (unsigned long long)c.draw,
            (unsigned long long)c.drawIndexed, (unsigned long long)c.drawIndirect,
            (unsigned long long)c.executeBundles, (unsigned long long)c.instances,
            (unsigned long long)c.triangles);
    };
    for (const auto& row : rows) {
        printRow(row.name, row.pipelinesCreated, row.counters);
        if (row.bundlesRecorded > 0) {
            printRow(row.name + ": inside its bundles", 0, row.bundleContents);
        }
    }
    std::printf(
        "\nPer frame; \"inside its bundles\" rows count the commands recorded once into "
        "the render bundles that the frame replays.\n");
    bool gpuDrawn = false;
    for (const auto& row : rows) {
        gpuDrawn = gpuDrawn || row.gpuDrawn.has_value();
    }
    if (gpuDrawn) {
        std::printf(
            "\nTriangles the GPU decided to draw (culling on the GPU, the visibility buffer), "
            "read back after the frame:\n\n| strategy | hardware rasteriser | compute "
            "rasteriser |\n|---|---:|---:|\n");
        for (const auto& row : rows) {
            if (row.gpuDrawn) {
                std::printf("| %s | %llu | %llu |\n", row.name.c_str(),
                            (unsigned long long)row.gpuDrawn->hardware,
                            (unsigned long long)row.gpuDrawn->compute);
            }
        }
    }
    if (!rows.empty() && rows.front().animation &&
        rows.front().animation->evaluation == render::AnimationEvaluation::Gpu) {
        const render::AnimationFrameStats& a = *rows.front().animation;
        std::printf(
            "\nAnimation evaluated on the GPU, the frame at --time: %u compute "
            "dispatches (%u animated nodes, %u nodes below them in %u levels, %u "
            "instances, %u joints), %u buffer copies, %llu bytes written by the CPU.\n",
            a.gpu.dispatches, a.gpu.animatedNodes, a.gpu.worldNodes, a.gpu.levels, a.gpu.instances,
            a.gpu.joints, a.gpu.copies, (unsigned long long)a.bytesWritten);
    } else if (!rows.empty() && rows.front().animation) {
        const render::AnimationFrameStats& a = *rows.front().animation;
        std::printf(
            "\nAnimation, the frame from --time - 1/60 s to --time: %u channels "
            "evaluated, %u nodes changed, %u joint matrices and %u morph weights "
            "written, %u instance transforms written, %llu bytes written.\n",
            a.player.channelsEvaluated, a.player.nodesChanged, a.upload.jointsWritten,
            a.upload.weightsWritten, a.instancesWritten, (unsigned long long)a.bytesWritten);
    }
}

int runStats(const StatsOptions& options, const GlobalOptions& global) {
    const auto choices = parseStrategySelection(options.strategies, options.bundle);
    if (!choices) {
        return reportError(choices.error());
    }
    auto scene = loadModel(options.model, {}, global);
    if (!scene) {
        return reportError(scene.error());
    }
    auto context = createContext(global);
    if (!context) {
        return reportError(context.error());
    }
    render::RendererOptions rendererOptions;
    rendererOptions.target = {options.width, options.height, 1};
    rendererOptions.animation = *render::animationEvaluationFromName(options.animate);
    auto renderer = render::Renderer::create(*context, rendererOptions);
    if (!renderer) {
        return reportError(renderer.error());
    }
    const auto camera = render::Camera::framing(scene->bounds, renderer->target().aspect());
    std::vector<StrategyStats> rows;
    for (const auto& choice : *choices) {
        if (auto prepared = renderer->prepare(*scene, choice.kind, choice.bundle); !prepared) {
            return reportError(prepared.error());
        }
        StrategyStats stats;
        stats.name = render::strategyChoiceName(choice);
        stats.pipelinesCreated = renderer->stats().pipelinesCreated;
        if (options.time) {
            if (!std::isfinite(*options.time)) {
                return reportError(makeError(ErrorCode::InvalidArgument,
                                             "--time must be a finite number of seconds."));
            }
            if (auto animated = renderer->setAnimationTime(*options.time - 1.0 / 60.0); !animated) {
                return reportError(animated.error());
            }
            if (auto animated = renderer->setAnimationTime(*options.time); !animated) {
                return reportError(animated.error());
            }
            stats.animation = renderer->animationStats();
        }
        renderer->setTriangleCounting(true);
        const auto frame = renderer->renderFrame(camera);
        auto history = renderer->takeTriangleHistory();
        renderer->setTriangleCounting(false);
        if (!history) {
            return reportError(history.error());
        }
        if (!history->empty()) {
            stats.gpuDrawn = history->back();
        }
        stats.counters = frame.counters;
        stats.bundleContents = frame.bundleContents;
        stats.bundlesRecorded = renderer->stats().bundlesRecorded;
        stats.encodeMilliseconds = frame.encodeMilliseconds;
        if (auto image = renderer->readImage(); !image) {
            return reportError(image.error());
        }
        rows.push_back(stats);
    }
    const std::string adapter = context->adapterDescription().summary();
    if (options.json) {
        nlohmann::json report = {{"model", options.model}, {"adapter", adapter}};
        for (const auto& row : rows) {
            report["strategies"].push_back(toJson(row));
        }
        std::printf("%s\n", report.dump(2).c_str());
    } else {
        printMarkdown(options.model, adapter, rows);
    }
    return kExitOk;
}

}  // namespace

void addStatsCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<StatsOptions>();
    auto* command = app.add_subcommand(
        "stats", "Count the WebGPU calls of one frame of a model, for every strategy.");
    command->add_option("model", options->model, "The .gltf or .glb file")->required();
    command->add_option("-s,--strategy", options->strategies,
                        "Only these strategies (repeatable; default: all; a direct one with "
                        "+bundle, e.g. naive+bundle, is recorded once into a render bundle)");
    command->add_flag("--bundle", options->bundle,
                      "Also count each strategy recorded once into render bundles (materials "
                      "and gpu-culling as bundles and gpu-culling-bundles, the others as "
                      "NAME+bundle)");
    command->add_flag("--json", options->json, "Print JSON instead of a Markdown table");
    command->add_option("--time", options->time,
                        "Animate to this time (seconds) and report one frame's animation work");
    command
        ->add_option("--animate", options->animate,
                     "Evaluate animation on the cpu (scene::AnimationPlayer) or the gpu "
                     "(compute passes)")
        ->check(CLI::IsMember({"cpu", "gpu"}));
    command->callback([options, &global, &exitCode] { exitCode = runStats(*options, global); });
}

}  // namespace encore::app
