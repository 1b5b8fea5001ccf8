// encore.Renderer.batch: the keyword arguments of `encore batch` turned into its options, and
// the summary it returns.

#include <pybind11/stl.h>

#include <atomic>
#include <optional>
#include <tuple>

#include "BatchArguments.h"
#include "ModuleErrors.h"
#include "Renderer.h"
#include "batch/BatchOptionsValidation.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"
#include "encore/image/HdrImage.h"

namespace encore::python {
namespace {

py::dict summaryDict(const batch::BatchSummary& result) {
    py::dict stages;
    stages["load"] = result.stages.load;
    stages["upload"] = result.stages.upload;
    stages["render"] = result.stages.render;
    stages["gpu"] = result.stages.gpu;
    stages["readback"] = result.stages.readback;
    stages["encode"] = result.stages.encode;
    stages["load_cpu"] = result.stages.loadCpu;
    stages["encode_cpu"] = result.stages.encodeCpu;
    py::list failures;
    for (const batch::Failure& failure : result.failures) {
        py::dict entry;
        entry["file"] = failure.file.string();
        entry["stage"] = failure.stage;
        // Messages may quote file contents: invalid UTF-8 is replaced, as failures.jsonl does.
        entry["error"] = py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(
            failure.error.data(), Py_ssize_t(failure.error.size()), "replace"));
        failures.append(entry);
    }
    py::dict dict;
    dict["total"] = result.total;
    dict["rendered"] = result.rendered;
    dict["failed"] = result.failed;
    dict["skipped"] = result.skipped;
    dict["views"] = result.views;
    dict["seconds"] = result.seconds;
    dict["interrupted"] = result.interrupted;
    dict["loads_left_behind"] = result.loadsLeftBehind;
    dict["stages"] = stages;
    dict["failures"] = failures;
    py::list devices;
    for (const batch::DeviceSummary& device : result.devices) {
        py::dict entry;
        entry["device"] = device.device;
        entry["adapter"] = device.adapter;
        entry["models"] = device.models;
        entry["views"] = device.views;
        devices.append(entry);
    }
    dict["devices"] = devices;
    return dict;
}

}  // namespace

// Runs the job of `encore batch` on this renderer's device.
py::dict Renderer::runBatch(const py::object& inputs,
                            const std::string& output,
                            std::uint32_t views,
                            std::uint32_t randomViews,
                            std::uint64_t seed,
                            float elevation,
                            const py::object& distance,
                            const py::object& fov,
                            bool normalize,
                            const py::object& size,
                            std::optional<std::uint32_t> samples,
                            std::size_t jobs,
                            std::uint64_t memoryLimitMiB,
                            bool strict,
                            bool normals,
                            bool depth,
                            float topLightLux,
                            const std::string& pngCompression,
                            bool failureLog,
                            std::uint32_t renderers,
                            float lodError,
                            const std::string& distribution,
                            float jitter,
                            const std::optional<std::string>& environment,
                            const std::optional<std::string>& environmentDirectory,
                            const py::object& environmentRotation,
                            const py::object& environmentIntensity,
                            const std::string& layout,
                            std::uint32_t blankThreshold,
                            const py::object& variant,
                            const py::object& variants,
                            const py::object& passes,
                            const std::string& segmentation,
                            const std::string& depthFormat,
                            double modelTimeout,
                            std::uint32_t maxTextureSize,
                            std::uint32_t shards,
                            std::uint64_t shardSize,
                            const std::string& pngFiltering,
                            bool allowUrisOutside) {
    batch::BatchOptions options;
    options.strategy = mStrategy;
    options.chooseStrategyPerModel = !mStrategy;  // "auto" or none given.
    options.shards = shards;
    options.shardBytes = shardSize;
    options.modelTimeoutSeconds = modelTimeout;  // Checked by validateBatchOptions.
    options.maxTextureSize = maxTextureSize;
    options.variant = variantArgument(variant);
    if (!variants.is_none()) {
        if (!py::isinstance<py::str>(variants) || variants.cast<std::string>() != "all") {
            throw py::value_error("variants must be None or \"all\"");
        }
        if (!options.variant.empty()) {
            throw py::value_error("give variant= or variants=\"all\", not both");
        }
        options.allVariants = true;
    }
    if (!(lodError >= 0.0f)) {
        throw py::value_error("lod_error must be a number of pixels, 0 or more");
    }
    options.lodErrorPixels = lodError;  // With the strategy that chooses the levels.
    if (renderers < 1 || renderers > batch::kMaxRenderers) {
        // As `encore batch --renderers` takes them.
        throw py::value_error("renderers must be 1 to " + std::to_string(batch::kMaxRenderers));
    }
    options.renderers = renderers;
    std::tie(options.width, options.height) = imageSize(size);
    options.samples = samples.value_or(mSamples);
    if (options.samples != 1 && options.samples != 4) {
        throw py::value_error("samples must be 1 or 4");
    }
    options.output = output;
    options.views = rigOptions(
        {randomViews > 0 ? randomViews : views, elevation, distance, fov,
         randomViews > 0 ? batch::CameraDistribution::Sphere : cameraDistribution(distribution),
         seed, normalize, jitter});
    applyLighting(options, environment, environmentDirectory, environmentRotation,
                  environmentIntensity);
    options.layout = named(batch::outputLayoutNames(), layout, "layout");
    options.blankThreshold = blankThreshold;
    options.jobs = jobs;
    options.memoryLimitBytes = memoryLimitMiB << 20;
    options.strict = strict;
    options.allowUrisOutside = allowUrisOutside;
    options.images.normals = normals;
    options.images.depth = depth;
    applyBatchPasses(passes, segmentation, depthFormat, options.images);
    options.topLightLux = topLightLux;
    const auto compression = image::pngCompressionFromName(pngCompression);
    if (!compression) {
        // As `encore batch --png-compression` takes it.
        throw py::value_error("png_compression must be \"small\" or \"fast\"");
    }
    options.pngCompression = *compression;
    options.pngFiltering = named(batch::pngFilteringNames(), pngFiltering, "png_filtering");
    options.writeFailureLog = failureLog;
    if (auto valid = batch::validateBatchOptions(options); !valid) {
        throw py::value_error(valid.error().message);
    }
    const std::vector<batch::BatchInput> models = batchInputs(inputs);
    // Python runs signal handlers only when the interpreter gets the GIL back: look for one
    // as progress is reported. A KeyboardInterrupt (or a handler's exception) stops the
    // batch as SIGINT stops the command, the models in flight finished, and is raised after.
    std::atomic<bool> stop{false};
    std::optional<py::error_already_set> interrupt;
    options.stop = &stop;
    options.progress = [&](const batch::BatchProgress&) {
        py::gil_scoped_acquire acquire;
        if (!interrupt && PyErr_CheckSignals() != 0) {
            interrupt.emplace();  // Takes the exception out of the interpreter.
            stop = true;
        }
    };
    Result<batch::BatchSummary> summary = makeError(ErrorCode::InvalidArgument, "");
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);  // One job on the device at a time.
        // The batch renderer of the previous call when the options allow: encore.dask calls
        // this once per task, and building it (environment maps, pipelines) would otherwise
        // cost every task as much as a few models.
        summary = batch::runBatch(*mBatchRenderers, models, options);
    }
    if (interrupt) {
        throw std::move(*interrupt);
    }
    return summaryDict(valueOrThrow(std::move(summary)));
}

// The environment keywords of batch(): one file, or a folder's files drawn per model, and
// the rotation ("random", degrees or a (min, max) pair) and intensity drawn per model.
void Renderer::applyLighting(batch::BatchOptions& options,
                             const std::optional<std::string>& environment,
                             const std::optional<std::string>& directory,
                             const py::object& rotation,
                             const py::object& intensity) {
    if (environment && directory) {
        throw py::value_error("environment and environment_dir exclude each other");
    }
    if (environment) {
        Result<image::HdrImage> panorama = makeError(ErrorCode::InvalidArgument, "");
        {
            py::gil_scoped_release release;
            panorama = image::readHdr(*environment);
        }
        options.renderer.environmentImage =
            std::make_shared<image::HdrImage>(valueOrThrow(std::move(panorama)));
        options.lighting.environmentName = *environment;
    }
    if (directory) {
        options.lighting.environmentDirectory = *directory;
        if (auto listed = batch::environmentFiles(*directory); !listed) {
            throw py::value_error(listed.error().message);
        }
    }
    if (py::isinstance<py::str>(rotation)) {
        if (rotation.cast<std::string>() != "random") {
            throw py::value_error(
                "environment_rotation must be degrees, a (min, max) pair or \"random\"");
        }
        options.lighting.rotationDegrees = batch::ValueRange(0.0f, 360.0f);
    } else if (!rotation.is_none()) {
        options.lighting.rotationDegrees = valueRange(rotation, "environment_rotation");
    }
    if (!intensity.is_none()) {
        options.lighting.intensity = valueRange(intensity, "environment_intensity");
    }
}

}  // namespace encore::python
