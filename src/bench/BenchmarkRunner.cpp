#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <thread>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define ENCORE_HAS_CALLGRIND 1
#else
#define ENCORE_HAS_CALLGRIND 0
#endif

#include "bench/Benchmark.h"
#include "core/Elapsed.h"
#include "encore/render/Renderer.h"
#include "gpu/GpuTimer.h"
#include "render/Animometer.h"
#include "render/CameraPath.h"
#include "render/renderer/RendererCore.h"
#include "scene/CrowdGenerator.h"
#include "scene/SceneGenerator.h"

namespace encore::bench {

namespace {

void startInstructionCount(bool enabled) {
#if ENCORE_HAS_CALLGRIND
    if (enabled) {
        CALLGRIND_ZERO_STATS;
        CALLGRIND_START_INSTRUMENTATION;
    }
#else
    (void)enabled;
#endif
}

void stopInstructionCount(bool enabled, const std::string& label) {
#if ENCORE_HAS_CALLGRIND
    if (enabled) {
        CALLGRIND_STOP_INSTRUMENTATION;
        CALLGRIND_DUMP_STATS_AT(label.c_str());
    }
#else
    (void)enabled;
    (void)label;
#endif
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

std::string cpuModel() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0) {
            return line.substr(line.find(':') + 2);
        }
    }
    return "unknown CPU";
}

// Bounds a timed warm-up whose frames are slow (CPU adapters, huge scenes).
constexpr std::uint32_t kMaxExtraWarmupFrames = 10000;

double warmupDuration(const gpu::Context& context, const BenchOptions& options) {
    if (options.warmupSeconds) {
        return *options.warmupSeconds;
    }
    // A CPU renderer has no clocks to raise.
    return context.adapterDescription().adapterType == wgpu::AdapterType::CPU ? 0.0 : 0.5;
}

// Renders warm-up plus measured frames one at a time (the CPU waits for the GPU between
// frames, so one frame's CPU work never queues behind the last) and fills the timings.
// `renderFrame(index)` renders one frame and returns its timing.
template <typename RenderFrame>
void measureFrames(gpu::Context& context,
                   const BenchOptions& options,
                   const std::string& label,
                   BenchResult& result,
                   RenderFrame&& renderFrame) {
    std::vector<double> encode;
    std::vector<double> submit;
    std::vector<double> cpu;
    std::vector<double> gpu;
    const std::uint32_t warmup = options.callgrind ? 0 : options.warmup;
    const auto warmupStart = std::chrono::steady_clock::now();
    for (std::uint32_t frame = 0; frame < warmup; ++frame) {
        renderFrame(frame);
        context.waitForIdle();
    }
    // Then the last warm-up frame again until the warm-up time is over.
    const double warmupMilliseconds = warmup > 0 ? warmupDuration(context, options) * 1000.0 : 0.0;
    for (std::uint32_t extra = 0;
         extra < kMaxExtraWarmupFrames && millisecondsSince(warmupStart) < warmupMilliseconds;
         ++extra) {
        renderFrame(warmup - 1);
        context.waitForIdle();
        ++result.warmupFrames;
    }
    result.warmupFrames += warmup;
    startInstructionCount(options.callgrind);
    for (std::uint32_t frame = warmup; frame < warmup + options.frames; ++frame) {
        const render::FrameTiming timing = renderFrame(frame);
        context.waitForIdle();
        encode.push_back(timing.encodeMilliseconds);
        submit.push_back(timing.submitMilliseconds);
        cpu.push_back(timing.cpuMilliseconds());
        if (timing.gpuMilliseconds) {
            gpu.push_back(*timing.gpuMilliseconds);
        }
    }
    stopInstructionCount(options.callgrind, label);
    result.encode = render::Percentiles::of(std::move(encode));
    result.submit = render::Percentiles::of(std::move(submit));
    result.cpu = render::Percentiles::of(std::move(cpu));
    if (!gpu.empty()) {
        result.gpu = render::Percentiles::of(std::move(gpu));
    }
}

float frameTime(std::uint32_t frame) {
    return float(frame) / 60.0f;
}

// Measures one strategy on one scene, seen whole (Camera::framing) or, with `path`, from the
// path's camera: the warm-up frames from its start, the measured frames once round it.
// With `animate`, every frame first sets the animation time (its CPU time counts as encoding).
Result<BenchResult> measure(gpu::Context& context,
                            render::Renderer& renderer,
                            const scene::SceneData& scene,
                            render::StrategyChoice choice,
                            const BenchOptions& options,
                            gpu::GpuTimer* timer,
                            std::optional<render::AnimationEvaluation> animate,
                            const std::optional<render::CameraPath>& path) {
    ENCORE_TRY(renderer.setAnimationEvaluation(animate.value_or(render::AnimationEvaluation::Cpu)));
    // Every measured frame animates: past an animation's end it starts again (clamped, the CPU
    // path would stop changing anything after one play).
    renderer.setPlaybackMode(scene::PlaybackMode::Loop);
    ENCORE_TRY(renderer.prepare(scene, choice.kind, choice.bundle));
    const float aspect = renderer.target().aspect();
    const render::Camera framing = render::Camera::framing(scene.bounds, aspect);
    const std::uint32_t warmup = options.callgrind ? 0 : options.warmup;
    auto cameraOf = [&](std::uint32_t frame) {
        if (!path) {
            return framing;
        }
        const std::uint32_t measured = frame < warmup ? 0 : frame - warmup;
        if (options.pathStep > 0.0f) {
            return path->cameraAtDistance(options.pathStep * float(measured), aspect);
        }
        return path->camera(measured, options.frames, aspect);
    };
    BenchResult result;
    result.strategy = render::strategyChoiceName(choice);
    result.objects = scene.instances.size();
    internals(renderer).setGpuTimer(options.callgrind ? nullptr : timer);
    if (animate) {
        result.animation = std::string(render::animationEvaluationName(*animate));
    }
    Result<void> animated;
    std::vector<double> animationTimes;
    std::map<std::string, std::vector<double>> passTimes;
    std::vector<double> spanTimes;
    measureFrames(context, options, result.strategy, result, [&](std::uint32_t frame) {
        double animationMilliseconds = 0.0;
        if (animate) {
            const auto start = std::chrono::steady_clock::now();
            if (auto set = renderer.setAnimationTime(frameTime(frame)); !set && animated) {
                animated = set;
            }
            animationMilliseconds = millisecondsSince(start);
            if (frame >= (options.callgrind ? 0 : options.warmup)) {
                animationTimes.push_back(animationMilliseconds);
            }
        }
        if (frame == warmup) {
            renderer.setTriangleCounting(true);  // The measured frames only.
        }
        const render::FrameResult rendered =
            renderer.renderFrame(cameraOf(frame), frameTime(frame));
        result.frame = rendered.counters;
        result.bundleContents = rendered.bundleContents;
        if (frame >= warmup) {
            result.trianglesSubmitted.push_back(rendered.trianglesSubmitted);
            if (rendered.gpuMilliseconds && timer && !options.callgrind) {
                std::map<std::string, double> frameTimes;
                for (const gpu::GpuTimer::TimedPass& pass : timer->lastPasses()) {
                    frameTimes[pass.label] += pass.milliseconds;
                }
                for (const auto& [label, milliseconds] : frameTimes) {
                    passTimes[label].push_back(milliseconds);
                }
                if (const std::optional<double> span = timer->lastSpan()) {
                    spanTimes.push_back(*span);
                }
            }
        }
        render::FrameTiming timing(rendered);
        timing.encodeMilliseconds += animationMilliseconds;
        return timing;
    });
    ENCORE_TRY(animated);
    for (auto& [label, times] : passTimes) {
        result.gpuPasses[label] = render::Percentiles::of(std::move(times));
    }
    if (!spanTimes.empty()) {
        result.gpuSpan = render::Percentiles::of(std::move(spanTimes));
    }
    auto drawn = renderer.takeTriangleHistory();
    renderer.setTriangleCounting(false);
    if (!drawn) {
        return drawn.error().withContext("Benchmarking " + result.strategy);
    }
    const render::Strategy* strategy = internals(renderer).strategy();
    const auto gpuCounts = strategy ? strategy->report().gpuTriangleCounts
                                    : std::optional<render::GpuTriangleCounts>{};
    const bool computeRaster = gpuCounts && gpuCounts->computeOffset;
    for (const render::DrawnTriangles& frame : *drawn) {
        result.trianglesDrawn.push_back(frame.total());
        if (computeRaster) {
            result.trianglesCompute.push_back(frame.compute);
        }
    }
    if (animate) {
        result.animationCpu = render::Percentiles::of(std::move(animationTimes));
        result.animationWork = renderer.animationStats();
    }
    internals(renderer).setGpuTimer(nullptr);
    ENCORE_TRY(context.checkNoErrors("Benchmarking " + result.strategy));
    return result;
}

// Measures one configuration of the Animometer scene.
Result<BenchResult> measureAnimometer(gpu::Context& context,
                                      const render::AnimometerOptions& animometer,
                                      const BenchOptions& options,
                                      gpu::GpuTimer* timer) {
    shaders::ShaderLibrary shaders(context.device());
    ENCORE_TRY_ASSIGN(auto scene, render::AnimometerScene::create(context, shaders, animometer));
    BenchResult result;
    result.scene = "animometer";
    result.label = "animometer " + std::to_string(animometer.triangles) + " triangles";
    result.objects = animometer.triangles;
    measureFrames(context, options, scene.describe(), result, [&](std::uint32_t frame) {
        return scene.renderFrame(frameTime(frame), options.callgrind ? nullptr : timer);
    });
    result.frame = scene.lastFrameCounters();
    result.bundleContents = scene.bundleContents();
    ENCORE_TRY(context.checkNoErrors("Benchmarking " + scene.describe()));
    return result;
}

}  // namespace

std::string_view generatedSceneName(GeneratedScene scene) {
    switch (scene) {
        case GeneratedScene::Grid:
            return "grid";
        case GeneratedScene::Flythrough:
            return "flythrough";
        case GeneratedScene::City:
            return "city";
    }
    return "unknown";
}

std::optional<GeneratedScene> generatedSceneFromName(std::string_view name) {
    for (const auto scene :
         {GeneratedScene::Grid, GeneratedScene::Flythrough, GeneratedScene::City}) {
        if (generatedSceneName(scene) == name) {
            return scene;
        }
    }
    return std::nullopt;
}

std::string dawnVersion() {
    return ENCORE_DAWN_VERSION;
}

Result<BenchReport> runBenchmarks(gpu::Context& context,
                                  const BenchOptions& options,
                                  const ProgressCallback& progress) {
    if (options.frames == 0) {
        return makeError(ErrorCode::InvalidArgument, "The number of frames must be at least 1.");
    }
    BenchReport report;
    report.date = utcNow();
    report.adapter = context.adapterDescription();
    report.dawnVersion = dawnVersion();
    report.cpu = cpuModel();
    report.cores = std::thread::hardware_concurrency();
    report.options = options;
    report.options.warmupSeconds = warmupDuration(context, options);
    // Under callgrind a spinning wait would add a varying number of polls to the count.
    const gpu::WaitMode previousWait = context.waitMode();
    context.setWaitMode(options.callgrind ? gpu::WaitMode::Block : options.gpuWait);
    struct RestoreWait {
        gpu::Context& context;
        gpu::WaitMode mode;
        ~RestoreWait() { context.setWaitMode(mode); }
    } restoreWait{context, previousWait};

    std::vector<render::StrategyChoice> strategies = options.strategies;
    if (strategies.empty()) {
        for (auto kind : render::allStrategies()) {
            strategies.push_back({kind, false});
        }
    }
    ENCORE_TRY_ASSIGN(
        auto renderer,
        render::Renderer::create(context, {{options.width, options.height, options.samples}}));
    renderer.setCullingOptions(options.culling);
    report.environmentMilliseconds = renderer.stats().environmentBuildMilliseconds;
    // Room for every pass of the visibility strategy's two phases, even with each step timed
    // apart (--gpu-steps).
    auto timer = gpu::GpuTimer::create(context, 16);
    report.timestamps = timer.has_value() && !options.callgrind && options.gpuTimer;
    gpu::GpuTimer* timerPointer = report.timestamps ? &*timer : nullptr;
    if (timerPointer) {
        timerPointer->setStepDetail(options.gpuSteps);
    }

    auto runScene = [&](const scene::SceneData& scene, const std::string& kind,
                        const std::string& sceneLabel,
                        std::optional<render::AnimationEvaluation> animate,
                        const std::optional<render::CameraPath>& path = {}) -> Result<void> {
        const std::string label = animate
                                      ? sceneLabel + ", animation on the " +
                                            std::string(render::animationEvaluationName(*animate))
                                      : sceneLabel;
        // The GPU-culling and visibility strategies once more with frustum culling alone, when
        // asked: the baseline that occlusion culling and levels of detail are measured against.
        struct Measurement {
            render::StrategyChoice strategy;
            render::CullingOptions culling;
            std::string suffix;
        };
        std::vector<Measurement> measurements;
        for (auto strategy : strategies) {
            measurements.push_back({strategy, options.culling, ""});
            const bool culls = strategy.kind == render::StrategyKind::GpuCulling ||
                               strategy.kind == render::StrategyKind::GpuCullingBundles ||
                               strategy.kind == render::StrategyKind::Visibility;
            if (culls && options.frustumBaseline) {
                render::CullingOptions frustumOnly = options.culling;  // Raster sizes kept.
                frustumOnly.occlusion = false;
                frustumOnly.levelsOfDetail = false;
                measurements.push_back({strategy, frustumOnly, " (frustum only)"});
            }
        }
        for (const Measurement& measurement : measurements) {
            const std::string name =
                render::strategyChoiceName(measurement.strategy) + measurement.suffix;
            if (progress) {
                progress(label + " / " + name);
            }
            renderer.setCullingOptions(measurement.culling);
            auto result = measure(context, renderer, scene, measurement.strategy, options,
                                  timerPointer, animate, path);
            if (!result && result.error().code == ErrorCode::Unsupported) {
                report.skipped.push_back(label + " / " + name + ": " + result.error().message);
                continue;
            }
            if (!result) {
                return result.error().withContext(label);
            }
            result->scene = kind;
            result->label = label;
            result->strategy = name;
            report.results.push_back(std::move(*result));
        }
        renderer.setCullingOptions(options.culling);
        return {};
    };

    const std::vector<GeneratedScene> generatedScenes =
        options.scenes.empty() ? std::vector{GeneratedScene::Grid} : options.scenes;
    for (const GeneratedScene kind : generatedScenes) {
        for (std::uint32_t objects : options.objectCounts) {
            scene::GeneratorOptions generator;
            generator.objectCount = objects;
            generator.meshCount = options.meshes;
            generator.materialCount = options.materials;
            generator.tessellation = options.tessellation;
            generator.textures = options.textures;
            generator.layout = kind == GeneratedScene::Flythrough ? scene::SceneLayout::Lattice
                               : kind == GeneratedScene::City     ? scene::SceneLayout::City
                                                                  : scene::SceneLayout::Grid;
            ENCORE_TRY_ASSIGN(auto glb, scene::generateSceneGlb(generator));
            // The grid keeps the name its reports have always had.
            const std::string name = kind == GeneratedScene::Grid
                                         ? std::string("generated")
                                         : std::string(generatedSceneName(kind));
            const std::string label = name + " " + std::to_string(objects) + " objects";
            ENCORE_TRY_ASSIGN(auto scene, scene::loadSceneFromMemory(glb, {}, label));
            ENCORE_TRY(runScene(scene, name, label, std::nullopt,
                                render::CameraPath::forLayout(generator)));
        }
    }
    // Scenes run once still, or once per requested animation evaluation.
    auto runAnimated =
        [&](const scene::SceneData& scene, const std::string& kind, const std::string& label,
            const std::vector<render::AnimationEvaluation>& evaluations) -> Result<void> {
        if (evaluations.empty()) {
            return runScene(scene, kind, label, std::nullopt);
        }
        for (const auto evaluation : evaluations) {
            ENCORE_TRY(runScene(scene, kind, label, evaluation));
        }
        return {};
    };
    for (std::uint32_t characters : options.crowdCharacters) {
        ENCORE_TRY_ASSIGN(auto glb, scene::generateCrowdGlb({characters}));
        const std::string label = "crowd of " + std::to_string(characters) + " characters";
        ENCORE_TRY_ASSIGN(auto scene, scene::loadSceneFromMemory(glb, {}, label));
        const std::vector<render::AnimationEvaluation> both = {render::AnimationEvaluation::Cpu,
                                                               render::AnimationEvaluation::Gpu};
        ENCORE_TRY(
            runAnimated(scene, "crowd", label, options.animate.empty() ? both : options.animate));
    }
    for (std::uint32_t triangles : options.animometerTriangles) {
        for (const bool dynamicOffsets : {false, true}) {
            for (const bool bundle : {false, true}) {
                render::AnimometerOptions animometer;
                animometer.triangles = triangles;
                animometer.bundle = bundle;
                animometer.dynamicOffsets = dynamicOffsets;
                animometer.width = options.width;
                animometer.height = options.height;
                const std::string strategy = std::string("animometer-") +
                                             (dynamicOffsets ? "dynamic-offsets-" : "") +
                                             (bundle ? "bundle" : "direct");
                if (progress) {
                    progress("animometer " + std::to_string(triangles) + " / " + strategy);
                }
                auto result = measureAnimometer(context, animometer, options, timerPointer);
                if (!result && result.error().code == ErrorCode::Unsupported) {
                    report.skipped.push_back("animometer " + std::to_string(triangles) + " / " +
                                             strategy + ": " + result.error().message);
                    continue;
                }
                if (!result) {
                    return result.error();
                }
                result->strategy = strategy;
                report.results.push_back(std::move(*result));
            }
        }
    }
    for (const auto& model : options.models) {
        scene::LoadOptions loadOptions;
        loadOptions.allowUrisOutside = options.allowUrisOutside;
        ENCORE_TRY_ASSIGN(auto scene, scene::loadScene(model, loadOptions));
        ENCORE_TRY(runAnimated(scene, "model", model.filename().string(), options.animate));
    }
    return report;
}

}  // namespace encore::bench
