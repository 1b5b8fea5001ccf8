#pragma once

// The benchmark behind `encore bench`: strategies x scenes, each measured for a warm-up plus N
// frames, reporting per-frame CPU encode and submit time, GPU time from timestamp queries when
// the device has them, and the API call counts (median and p95). Compare results as ratios
// within one report: absolute numbers belong to the adapter and machine named in it.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/render/RendererStats.h"
#include "encore/render/StrategyKind.h"

namespace encore::bench {

// What the generated scenes (BenchOptions::objectCounts) look like and how the camera sees them.
enum class GeneratedScene : std::uint8_t {
    // The grid (scene::SceneLayout::Grid) seen whole from outside (Camera::framing), still.
    Grid,
    // The lattice (SceneLayout::Lattice) from a camera flying through it, one loop over the
    // measured frames (render::CameraPath::flythrough).
    Flythrough,
    // The city (SceneLayout::City) from street level, one loop round its middle over the
    // measured frames (render::CameraPath::city).
    City,
};
std::string_view generatedSceneName(GeneratedScene scene);  // "grid", "flythrough", "city".
std::optional<GeneratedScene> generatedSceneFromName(std::string_view name);

struct BenchOptions {
    // Occlusion culling and levels of detail of the gpu-culling and visibility strategies.
    render::CullingOptions culling;
    // Also measure each gpu-culling strategy and visibility with frustum culling alone ("<name>
    // (frustum only)"), in the same run.
    bool frustumBaseline = false;
    std::vector<std::uint32_t> objectCounts;  // Generated scenes, each of `scenes`.
    std::vector<GeneratedScene> scenes;       // Empty: the grid.
    // How far the camera of the fly-through and the city moves per frame, in scene units; 0:
    // once round its loop over the measured frames (render::CameraPath::camera).
    float pathStep = 0.0f;
    std::vector<std::filesystem::path> models;  // glTF files.
    bool allowUrisOutside = false;  // The models may read outside their folders (LoadOptions).
    std::vector<std::uint32_t> animometerTriangles;  // Animometer scenes (direct and bundle).
    std::vector<std::uint32_t> crowdCharacters;      // Animated crowds (scene::generateCrowdGlb).
    // Animate every frame (setAnimationTime, timed as part of encoding) with each of these
    // evaluations, measured separately; empty: scenes stand still, crowds use both.
    std::vector<render::AnimationEvaluation> animate;
    // Empty: every strategy, drawn directly or as its own bundled kind. A choice with `bundle`
    // measures a direct strategy recorded once into a render bundle (`naive+bundle`).
    std::vector<render::StrategyChoice> strategies;
    std::uint32_t meshes = 8;
    std::uint32_t materials = 4;
    std::uint32_t tessellation = 4;  // Small meshes: CPU rasterisers draw 100,000 objects.
    // Every other material of the generated scenes samples base colour and metallic-roughness
    // textures (scene::GeneratorOptions::textures); the others are texture-less.
    bool textures = true;
    std::uint32_t frames = 60;
    std::uint32_t warmup = 10;
    // Warm-up lasts at least this long too (seconds; unset: 0.5 on a GPU, 0 on a CPU adapter).
    // A GPU left idle while the CPU builds a scene drops its clocks (an H100 from 1,980 MHz to
    // 345) and takes longer than a few fast frames to raise them again: frames measured before
    // then run several times slower.
    std::optional<double> warmupSeconds;
    std::uint32_t width = 512;
    std::uint32_t height = 512;
    std::uint32_t samples = 1;  // Multisampling of the target: 1 or 4.
    // Repeatable instruction counts under valgrind: no warm-up frames, no GPU timer, and the
    // measured frames bracketed by CALLGRIND_START/STOP_INSTRUMENTATION (run valgrind with
    // --instr-atstart=no).
    bool callgrind = false;
    // Timestamp queries around every pass (GPU time per frame and per pass). Off, the CPU frame
    // is what an application pays, without the queries' commands, which grow with the passes.
    bool gpuTimer = true;
    // Under the GPU timer, each step of a pass of several (the visibility strategy's phases) as
    // a timed pass of its own: where the time goes, at the cost of the boundaries it adds.
    bool gpuSteps = false;
    // How the CPU waits for the GPU after each frame (and for the frame's timestamps). A
    // blocking wait lets the core sleep for as long as the GPU frame lasts; spinning keeps it
    // awake, so the next frame's CPU work does not depend on how long the GPU took.
    gpu::WaitMode gpuWait = gpu::WaitMode::Spin;
};

struct BenchResult {
    // "generated" (the grid), "flythrough", "city", "crowd", "model" or "animometer".
    std::string scene;
    std::string label;
    std::uint64_t objects = 0;  // Instances drawn (triangles for the Animometer).
    std::string strategy;
    std::string animation;  // "cpu" or "gpu" when animated (encode includes the evaluation).
    // Animated scenes: the CPU time of setAnimationTime per frame (part of encode), and what the
    // last measured frame's evaluation did.
    std::optional<render::Percentiles> animationCpu;
    render::AnimationFrameStats animationWork;
    render::Percentiles encode;
    render::Percentiles submit;
    render::Percentiles cpu;
    std::uint32_t warmupFrames = 0;  // Rendered before the measured ones (the timed warm-up's too).
    std::optional<render::Percentiles> gpu;
    // From the frame's first pass's beginning to its last pass's end (gpu::GpuTimer::lastSpan):
    // with the transfers between passes, which `gpu` (the sum of the passes) leaves out.
    std::optional<render::Percentiles> gpuSpan;
    // GPU time per pass label (gpu::GpuTimer::lastPasses, same-label passes of a frame summed):
    // where `gpu` goes, e.g. the culling passes, the depth pyramid and the scene passes.
    std::map<std::string, render::Percentiles> gpuPasses;
    render::DrawCounters frame;
    render::DrawCounters bundleContents;
    // Per measured frame (scenes drawn by a Renderer): what the draws could draw
    // (FrameResult::trianglesSubmitted), and what the GPU culling pass let through
    // (Renderer::takeDrawnTriangles, read back after the measured frames; empty for strategies
    // that do not cull on the GPU, which draw what they submit).
    std::vector<std::uint64_t> trianglesSubmitted;
    std::vector<std::uint64_t> trianglesDrawn;
    // Of trianglesDrawn, those rasterised in compute (the visibility strategy; empty for others).
    std::vector<std::uint64_t> trianglesCompute;
};

struct BenchReport {
    std::string date;  // ISO 8601, UTC.
    gpu::AdapterDescription adapter;
    std::string dawnVersion;
    std::string cpu;
    std::uint32_t cores = 0;
    BenchOptions options;
    bool timestamps = false;
    // Building the image-based-lighting maps (default studio environment) at start-up.
    double environmentMilliseconds = 0.0;
    std::vector<BenchResult> results;
    // Measurements the adapter cannot run (e.g. more bind groups than the driver survives),
    // each "<scene> / <strategy>: <reason>".
    std::vector<std::string> skipped;
};

// Called before each measurement with its label, for progress output.
using ProgressCallback = std::function<void(const std::string&)>;

Result<BenchReport> runBenchmarks(gpu::Context& context,
                                  const BenchOptions& options,
                                  const ProgressCallback& progress = {});

nlohmann::json toJson(const BenchReport& report);
// The JSON form of call counts used in reports (also by `encore stats --json`).
nlohmann::json toJson(const render::DrawCounters& counters);
std::string toMarkdown(const BenchReport& report);

// The Debian version of the Dawn package Encore was built against.
std::string dawnVersion();

}  // namespace encore::bench
