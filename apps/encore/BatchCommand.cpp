#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "BatchPassOptions.h"
#include "BatchReport.h"
#include "ByteSize.h"
#include "Commands.h"
#include "DeviceOptions.h"
#include "ShadingOptions.h"
#include "StrategyOptions.h"
#include "batch/BatchOptionsValidation.h"
#include "batch/OptionNames.h"
#include "encore/batch/Batch.h"

namespace encore::app {

namespace {

struct BatchCommandOptions {
    std::string input;
    std::string output;
    std::string size = "512";
    std::uint32_t samples = 4;
    std::uint32_t views = 12;
    std::uint32_t randomViews = 0;
    std::uint64_t seed = 0;
    std::string cameraDistribution = "orbit";
    float elevationDegrees = 30.0f;
    std::string distance = "1.5";
    std::string fovDegrees;  // Empty: batch::kDefaultHorizontalFovDegrees.
    float jitterDegrees = 0.0f;
    bool noNormalize = false;
    std::string environmentDirectory;
    std::string environmentRotation;   // Empty: none.
    std::string environmentIntensity;  // Empty: 1.
    std::string layout = "nerf";
    std::uint32_t blankThreshold = batch::kDefaultBlankThreshold;
    std::string strategy;  // Empty: batch::BatchOptions::strategy's default.
    std::optional<std::uint64_t> visibilityFromTriangles;  // Unset: auto's default.
    float lodErrorPixels = 0.0f;
    bool strict = false;
    double modelTimeoutSeconds = batch::kDefaultModelTimeoutSeconds;  // 0: none.
    std::uint32_t maxTextureSize = batch::kDefaultMaxTextureSize;
    std::uint32_t shards = 0;
    std::string shardSize;  // Empty: no limit.
    std::string variant;    // --variant N|NAME: that KHR_materials_variants variant only.
    std::string variants;   // --variants all: the default materials and every variant.
    bool normals = false;
    bool depth = false;
    BatchPassOptions passes;  // --albedo, --material, --segmentation, --depth-format, --hdr.
    float topLightLux = 0.0f;
    std::string pngCompression = "small";
    std::string pngFiltering = "auto";
    std::size_t jobs = 0;
    std::uint64_t memoryLimitMiB = 2048;
    std::size_t renderers = batch::kDefaultRenderers;
    std::string devices;  // --devices all|N,M,...; empty: the global device.
    bool quiet = false;
    ShadingOptions shading;
};

// Set by SIGINT and SIGTERM: the batch starts no more models, writes the views in flight and
// returns. A second signal stops the process at once, unless it came with the first: timeout(1)
// signals its child and then the child's process group, so the batch gets each signal twice
// within microseconds, and the second used to kill it (exit 143) when a thread had taken the
// first in between.
std::atomic<bool> gStopRequested{false};
std::atomic<std::int64_t> gStopRequestedNs{0};
constexpr std::int64_t kSameStopRequestNs = 200'000'000;
static_assert(std::atomic<std::int64_t>::is_always_lock_free);

extern "C" void requestStop(int signal) {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);  // Async-signal-safe, as are the lock-free atomics.
    const std::int64_t ns = std::int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
    if (!gStopRequested.exchange(true)) {
        gStopRequestedNs = ns;
        return;
    }
    if (ns - gStopRequestedNs < kSameStopRequestNs) {
        return;
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

Result<std::pair<std::uint32_t, std::uint32_t>> parseSize(const std::string& text) {
    const std::size_t x = text.find('x');
    auto number = [](const std::string& part) -> long {
        if (part.empty() || part.size() > 5 || part.find_first_not_of("0123456789") != part.npos) {
            return -1;
        }
        return std::stol(part);
    };
    const long width = number(text.substr(0, x));
    const long height = x == std::string::npos ? width : number(text.substr(x + 1));
    if (width < 1 || height < 1 || width > 8192 || height > 8192) {
        return makeError(ErrorCode::InvalidArgument,
                         "--size takes W or WxH in pixels, each from 1 to 8192 ('" + text + "').");
    }
    return std::pair{std::uint32_t(width), std::uint32_t(height)};
}

// "X" or "MIN:MAX", each a finite number: what --distance, --fov and the environment's options
// take. `option` names the option in the error.
Result<batch::ValueRange> parseRange(const std::string& text, const std::string& option) {
    const auto number = [](const std::string& part, float& value) {
        char* end = nullptr;
        value = std::strtof(part.c_str(), &end);
        return !part.empty() && end == part.c_str() + part.size() && std::isfinite(value);
    };
    const std::size_t colon = text.find(':');
    batch::ValueRange range;
    const bool parsed =
        colon == std::string::npos
            ? number(text, range.min) && number(text, range.max)
            : number(text.substr(0, colon), range.min) && number(text.substr(colon + 1), range.max);
    if (!parsed) {
        return makeError(ErrorCode::InvalidArgument,
                         option + " takes a number or a range MIN:MAX ('" + text + "').");
    }
    return range;
}

// The camera and lighting options that take ranges, into `batchOptions`.
Result<void> applyVariations(const BatchCommandOptions& options,
                             batch::BatchOptions& batchOptions) {
    batch::ViewRigOptions& views = batchOptions.views;
    // The names were checked by the parser (CLI::IsMember over the same tables).
    views.distribution =
        options.randomViews > 0
            ? batch::CameraDistribution::Sphere
            : *batch::valueNamed(batch::cameraDistributionNames(), options.cameraDistribution);
    ENCORE_TRY_ASSIGN(views.distance, parseRange(options.distance, "--distance"));
    if (!options.fovDegrees.empty()) {
        ENCORE_TRY_ASSIGN(views.horizontalFovDegrees, parseRange(options.fovDegrees, "--fov"));
    }
    views.jitterDegrees = options.jitterDegrees;

    batch::LightingVariation& lighting = batchOptions.lighting;
    lighting.environmentDirectory = options.environmentDirectory;
    lighting.environmentName = options.shading.environment;
    if (options.environmentRotation == "random") {
        lighting.rotationDegrees = batch::ValueRange(0.0f, 360.0f);
    } else if (!options.environmentRotation.empty()) {
        ENCORE_TRY_ASSIGN(lighting.rotationDegrees,
                          parseRange(options.environmentRotation, "--environment-rotation"));
    }
    if (!options.environmentIntensity.empty()) {
        ENCORE_TRY_ASSIGN(lighting.intensity,
                          parseRange(options.environmentIntensity, "--environment-intensity"));
    }
    batchOptions.layout = *batch::valueNamed(batch::outputLayoutNames(), options.layout);
    batchOptions.blankThreshold = options.blankThreshold;
    return {};
}

// The adapters of --devices, or the one --device (or ENCORE_DEVICE) names.
Result<std::vector<std::size_t>> batchDevices(const BatchCommandOptions& options,
                                              const GlobalOptions& global) {
    if (options.devices.empty()) {
        ENCORE_TRY_ASSIGN(auto device, chosenDevice(global));
        return std::vector<std::size_t>{device};
    }
    if (global.device) {
        return makeError(ErrorCode::InvalidArgument,
                         "--device and --devices exclude each other: --devices lists them all.");
    }
    ENCORE_TRY_ASSIGN(auto adapters, gpu::listAdapters(global.allowNullBackend));
    return parseDeviceList(options.devices, adapters);
}

int runBatch(const BatchCommandOptions& options, const GlobalOptions& global) {
    batch::BatchOptions batchOptions;
    auto size = parseSize(options.size);
    if (!size) {
        return reportError(size.error());
    }
    std::tie(batchOptions.width, batchOptions.height) = *size;
    if (!options.strategy.empty() && options.strategy != "auto") {
        auto strategy = parseStrategyChoice(options.strategy, false);
        if (!strategy) {
            return reportError(strategy.error());
        }
        batchOptions.strategy = *strategy;
    }
    batchOptions.visibilityFromTriangles = options.visibilityFromTriangles;
    batchOptions.lodErrorPixels = options.lodErrorPixels;
    batchOptions.output = options.output;
    batchOptions.samples = options.samples;
    batchOptions.views.views = options.randomViews > 0 ? options.randomViews : options.views;
    batchOptions.views.seed = options.seed;
    batchOptions.views.elevationDegrees = options.elevationDegrees;
    batchOptions.views.normalize = !options.noNormalize;
    batchOptions.strict = options.strict;
    batchOptions.allowUrisOutside = global.allowUrisOutside;
    batchOptions.modelTimeoutSeconds = options.modelTimeoutSeconds;
    batchOptions.maxTextureSize = options.maxTextureSize;
    batchOptions.shards = options.shards;
    if (!options.shardSize.empty()) {
        auto bytes = parseByteSize(options.shardSize, "--shard-size");
        if (!bytes) {
            return reportError(bytes.error());
        }
        batchOptions.shardBytes = *bytes;
    }
    batchOptions.variant = options.variant;
    batchOptions.allVariants = options.variants == "all";
    batchOptions.images.normals = options.normals;
    batchOptions.images.depth = options.depth;
    applyBatchPassOptions(options.passes, batchOptions.images);
    batchOptions.topLightLux = options.topLightLux;
    batchOptions.pngCompression = *image::pngCompressionFromName(options.pngCompression);
    batchOptions.pngFiltering =
        *batch::valueNamed(batch::pngFilteringNames(), options.pngFiltering);
    batchOptions.jobs = options.jobs;
    batchOptions.memoryLimitBytes = options.memoryLimitMiB << 20;
    batchOptions.renderers = options.renderers;
    if (auto shading = applyShadingOptions(options.shading, batchOptions.renderer); !shading) {
        return reportError(shading.error());
    }
    // Usage errors before the device starts: the ranges, then the environment folder.
    if (auto varied = applyVariations(options, batchOptions); !varied) {
        return reportError(varied.error());
    }
    if (auto valid = batch::validateBatchOptions(batchOptions); !valid) {
        return reportError(valid.error());
    }
    if (!options.environmentDirectory.empty()) {
        if (auto listed = batch::environmentFiles(options.environmentDirectory); !listed) {
            return reportError(listed.error());
        }
    }

    auto inputs = batch::discoverInputs(options.input);
    if (!inputs) {
        return reportError(inputs.error());
    }
    // -v times the GPU's stages: timestamps need the device feature, asked for only then.
    batchOptions.gpuTimestamps = global.verbose;
    auto devices = batchDevices(options, global);
    if (!devices) {
        return reportError(devices.error());
    }
    // One context (device) and one set of renderers per entry of --devices.
    std::vector<gpu::Context> contexts;
    contexts.reserve(devices->size());
    for (std::size_t device : *devices) {
        auto context = createContext(global, /*timestamps=*/global.verbose, device);
        if (!context) {
            return reportError(context.error());
        }
        contexts.push_back(std::move(*context));
    }
    std::vector<std::unique_ptr<batch::BatchRenderer>> renderers;
    std::vector<batch::BatchRenderer*> deviceRenderers;
    for (gpu::Context& context : contexts) {
        renderers.push_back(std::make_unique<batch::BatchRenderer>(context));
        deviceRenderers.push_back(renderers.back().get());
    }

    // A live line on a terminal; every few seconds on a pipe or a file; none with --quiet.
    const bool terminal = ::isatty(STDERR_FILENO) == 1;
    const double interval = terminal ? 0.2 : 5.0;
    double lastPrinted = -interval;
    std::size_t startSkipped = 0;
    bool first = true;
    batchOptions.progress = [&](const batch::BatchProgress& progress) {
        if (first) {
            startSkipped = progress.skipped;  // Skipped models take no time: not in the ETA.
            first = false;
        }
        if (options.quiet || progress.seconds - lastPrinted < interval) {
            return;
        }
        lastPrinted = progress.seconds;
        const std::string line = progressLine(progress, startSkipped);
        std::fprintf(stderr, terminal ? "\r%s\033[K" : "%s\n", line.c_str());
    };
    gStopRequested = false;
    gStopRequestedNs = 0;
    batchOptions.stop = &gStopRequested;
    auto previousInt = std::signal(SIGINT, requestStop);
    auto previousTerm = std::signal(SIGTERM, requestStop);
    auto summary = batch::runBatch(deviceRenderers, *inputs, batchOptions);
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    if (terminal && !options.quiet) {
        std::fprintf(stderr, "\n");
    }
    if (!summary) {
        return reportError(summary.error());
    }
    printBatchSummary(*summary,
                      options.jobs ? options.jobs
                                   : std::size_t(std::max(1u, std::thread::hardware_concurrency())),
                      global.verbose);
    if (summary->failed > 0) {
        std::fprintf(stderr, "error: %zu models failed; see %s\n", summary->failed,
                     (std::filesystem::path(options.output) / "failures.jsonl").c_str());
        return kExitFailure;
    }
    return summary->interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace

void addBatchCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
    auto options = std::make_shared<BatchCommandOptions>();
    options->shading.background = "transparent";
    auto* command = app.add_subcommand(
        "batch",
        "Render many glTF models from orbit or random viewpoints into a dataset folder: per "
        "model RGBA PNGs, a NeRF transforms.json and metadata.json; reruns skip finished "
        "models.");
    command
        ->add_option("input", options->input,
                     "A folder (searched recursively for .gltf/.glb), a model, a text file with "
                     "one path per line, or a JSON list of paths")
        ->required();
    command->add_option("-o,--output", options->output, "The output folder")->required();
    command->add_option("--views", options->views, "Views per model on an orbit")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000));
    auto* random =
        command
            ->add_option("--random-views", options->randomViews,
                         "Views per model drawn uniformly on the sphere instead of the orbit")
            ->check(CLI::Range(1, 10000));
    command
        ->add_option("--camera-distribution", options->cameraDistribution,
                     "Where the views look from: orbit (evenly around, --elevation high), sphere "
                     "or upper-hemisphere (drawn uniformly, per model, from --seed)")
        ->capture_default_str()
        ->check(CLI::IsMember(batch::namesOf(batch::cameraDistributionNames())))
        ->excludes(random);
    command
        ->add_option("--seed", options->seed,
                     "Seeds everything drawn at random (directions, jitter, ranges, environments), "
                     "with each model's name: the same pictures for the same seed")
        ->capture_default_str();
    command
        ->add_option("--elevation", options->elevationDegrees,
                     "Orbit height above the horizon (degrees)")
        ->capture_default_str()
        ->check(CLI::Range(-90.0f, 90.0f))
        ->excludes(random);
    command
        ->add_option("--distance", options->distance,
                     "Camera distance from the centre (unit-box units unless --no-normalize), or "
                     "MIN:MAX: drawn per view")
        ->capture_default_str()
        ->type_name("D|MIN:MAX");
    command
        ->add_option("--fov", options->fovDegrees,
                     "Horizontal field of view in degrees, or MIN:MAX: drawn per view (default: a "
                     "35 mm lens on a 32 mm sensor)")
        ->type_name("DEG|MIN:MAX");
    command
        ->add_option("--camera-jitter", options->jitterDegrees,
                     "Move each view's direction by up to this many degrees in azimuth and "
                     "elevation (drawn from --seed)")
        ->check(CLI::Range(0.0f, 180.0f))
        ->type_name("DEG");
    command->add_flag("--no-normalize", options->noNormalize,
                      "Keep the model's size and position (default: scale into a unit box "
                      "centred at the origin)");
    command->add_option("--size", options->size, "Image size W or WxH in pixels")
        ->capture_default_str();
    command->add_option("--samples", options->samples, "Multisampling: 1 or 4")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 4}));
    command->add_option("-s,--strategy", options->strategy,
                        "Rendering strategy of every model, or auto (the default): per model, "
                        "visibility on a GPU for models of at least " +
                            std::to_string(batch::kAutoVisibilityTriangles) + " triangles (" +
                            std::to_string(batch::kAutoVisibilityTrianglesOneSample) +
                            " at --samples 1) and, at --samples 4, for those of only opaque, "
                            "static triangles whatever their size, else bundles "
                            "(gpu-culling-bundles with --lod-error); bundles on a CPU and with "
                            "extra images; metadata.json names the choice");
    command
        ->add_option("--visibility-from-triangles", options->visibilityFromTriangles,
                     "With --strategy auto: the triangles (summed over the instances) from which "
                     "a model is drawn with visibility, on any adapter that has the feature (a "
                     "CPU too), replacing auto's rule for opaque, static models. Default: " +
                         std::to_string(batch::kAutoVisibilityTriangles) + " on a GPU (" +
                         std::to_string(batch::kAutoVisibilityTrianglesOneSample) +
                         " at --samples 1)")
        ->type_name("N");
    command
        ->add_option("--lod-error", options->lodErrorPixels,
                     "Draw each instance at the coarsest level of detail whose simplification "
                     "error stays under this many pixels in the nearest view (levels are built "
                     "at load; a gpu-culling strategy or visibility chooses them). Default: full "
                     "detail")
        ->check(CLI::PositiveNumber)
        ->type_name("PIXELS");
    command->add_flag("--strict", options->strict,
                      "Treat loader warnings as errors (the model fails)");
    command
        ->add_option("--model-timeout", options->modelTimeoutSeconds,
                     "Abandon a model still loading or drawing after this many seconds of work "
                     "on it (failures.jsonl stage timeout) and go on; 0: no limit")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber)
        ->type_name("SECONDS");
    command
        ->add_option("--max-texture-size", options->maxTextureSize,
                     "Downscale larger images while loading (listed in metadata.json's "
                     "imagesDownscaled); 0: keep every size")
        ->capture_default_str()
        ->type_name("PIXELS");
    auto* variant = command->add_option(
        "--variant", options->variant,
        "Draw every model in this KHR_materials_variants variant (index or name) into "
        "OUT/<name>@<variant>; a model without it fails");
    command
        ->add_option("--variants", options->variants,
                     "all: draw every model with its default materials into OUT/<name> and in "
                     "each of its variants into OUT/<name>@<variant>, each a sample of its own")
        ->check(CLI::IsMember({"all"}))
        ->excludes(variant);
    command
        ->add_option("-j,--jobs", options->jobs,
                     "Threads for loading and encoding (default: all cores)")
        ->check(CLI::Range(1, 1024));
    command
        ->add_option("--memory-limit", options->memoryLimitMiB,
                     "MiB the models hold decoded at once (loaded ahead of the GPU or loading), "
                     "at most; a model alone past it fails")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 24));
    command
        ->add_option("--renderers", options->renderers,
                     "Models on the device at once: the next uploads while the GPU draws the "
                     "others (1: one after the other)")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{1}, batch::kMaxRenderers));
    command
        ->add_option("--devices", options->devices,
                     "Render on several GPUs at once: all (every adapter like the first: the "
                     "GPUs, not a CPU renderer beside them) or indices as `encore info` lists "
                     "them (0,1,...; one listed twice gets two devices)")
        ->type_name("all|N,M,...");
    command->add_flag("--normals", options->normals,
                      "Also write world-space normals per view (000_normal.png: n * 0.5 + 0.5)");
    auto* depth = command->add_flag("--depth", options->depth,
                                    "Also write 16-bit depth per view (000_depth.png; depth_scale "
                                    "in transforms.json)");
    addBatchPassOptions(*command, options->passes, depth);
    command
        ->add_option("--top-light", options->topLightLux,
                     "Add a directional light shining straight down, this many lux (the dataset "
                     "scripts' light from above)")
        ->check(CLI::NonNegativeNumber)
        ->type_name("LUX");
    command
        ->add_option("--png-compression", options->pngCompression,
                     "small: Paeth and runs for 8-bit images, libdeflate for 16-bit depth (the "
                     "default); fast: about a third less encoding time for views 25-30% larger "
                     "(depth nearly 3x), when encoding limits the batch")
        ->check(CLI::IsMember({"small", "fast"}))
        ->capture_default_str();
    command
        ->add_option("--png-filtering", options->pngFiltering,
                     "Where the PNG rows are filtered and the passes' samples made: gpu (a "
                     "compute pass; the pool only compresses), cpu, or auto: the GPU unless the "
                     "adapter is a CPU (lavapipe). The files are the same either way")
        ->check(CLI::IsMember(batch::namesOf(batch::pngFilteringNames())))
        ->capture_default_str();
    command
        ->add_option("--layout", options->layout,
                     "nerf: images and transforms.json; objaverse: also a 000.npy camera matrix "
                     "per view, as the Objaverse-XL scripts write them")
        ->capture_default_str()
        ->check(CLI::IsMember(batch::namesOf(batch::outputLayoutNames())));
    command
        ->add_option("--shards", options->shards,
                     "Write WebDataset .tar shards (OUT/shard-000000.tar ...: <name>.000.png, "
                     "<name>.transforms.json, ...) instead of a folder per model, about this many")
        ->check(CLI::Range(1u, 1000000u))
        ->type_name("N");
    command
        ->add_option("--shard-size", options->shardSize,
                     "Write WebDataset .tar shards, each finished once it holds this much (1GiB, "
                     "500MB, ...)")
        ->type_name("BYTES");
    command
        ->add_option("--blank-threshold", options->blankThreshold,
                     "A view covering fewer pixels is blank: listed in metadata.json (and a "
                     "failure with --strict); 0: none is")
        ->capture_default_str()
        ->type_name("PIXELS");
    command->add_flag("-q,--quiet", options->quiet, "No progress lines");
    addShadingOptions(*command, options->shading, /*environmentLevels=*/false);
    command
        ->add_option("--environment-dir", options->environmentDirectory,
                     "Light each model with one Radiance .hdr of this folder, drawn from --seed "
                     "and the model's name")
        ->excludes("--environment")
        ->type_name("DIR");
    command
        ->add_option("--environment-rotation", options->environmentRotation,
                     "Turns the environment about the vertical axis: degrees, MIN:MAX or random "
                     "(0:360), drawn per model")
        ->type_name("DEG|MIN:MAX|random");
    command
        ->add_option("--environment-intensity", options->environmentIntensity,
                     "Multiplies the environment's radiance: a number or MIN:MAX, drawn per model")
        ->type_name("X|MIN:MAX");
    command->callback([options, &global, &exitCode] { exitCode = runBatch(*options, global); });
}

}  // namespace encore::app
