// The Python module `encore`: the C++ library's batch rendering for Python code (data loaders,
// task systems). It wraps encore::batch and encore::render, not the executable.
//
//   renderer = encore.Renderer()              # one GPU device
//   scene = renderer.load("model.glb")        # encore.LoadError with the loader's message
//   images, intrinsics, cameras = renderer.render_views(scene, views=12, size=512)
//   renderer.batch("models/", "out/", views=12)  # the job of `encore batch`, returns its summary
//
// The GIL is released while files load and while the GPU renders. The package around it
// (python/encore/__init__.py) adds encore.batch and encore.dask.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "BatchArguments.h"
#include "ViewPasses.h"
#include "batch/BatchOptionsValidation.h"
#include "batch/TransformsJson.h"
#include "batch/ViewStrips.h"
#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"
#include "encore/batch/BatchRenderer.h"
#include "encore/batch/ViewRig.h"
#include "encore/gpu/Context.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"
#include "encore/render/VisibilityFeatures.h"
#include "encore/scene/MaterialVariants.h"
#include "encore/scene/SceneData.h"

namespace py = pybind11;

namespace encore::python {
namespace {

// Raised as encore.Error (GPU, I/O, arguments) and encore.LoadError (a model that does not
// load), each with the message `encore render` would print.
struct EncoreError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
struct LoadError : EncoreError {
    using EncoreError::EncoreError;
};

template <typename T>
T valueOrThrow(Result<T> result) {
    if (!result) {
        throw EncoreError(result.error().message);
    }
    return std::move(*result);
}

// ENCORE_DEVICE, as `encore --device` reads it: how a Dask worker (encore.dask) is given its
// GPU. Unset or empty: 0.
std::size_t deviceFromEnvironment() {
    const char* variable = std::getenv("ENCORE_DEVICE");
    if (!variable || !*variable) {
        return 0;
    }
    char* end = nullptr;
    const unsigned long long index = std::strtoull(variable, &end, 10);
    if (*end != '\0' || variable[0] == '-') {
        throw py::value_error(std::string("ENCORE_DEVICE='") + variable +
                              "' is not a device index (0, 1, ...: encore.adapters() lists them)");
    }
    return std::size_t(index);
}

// A loaded model: immutable, shared by the Python object and the renderer that prepared it.
struct Scene {
    std::shared_ptr<const scene::SceneData> data;
};

// A `variant=` keyword: None, a variant's name, or its index, as text (scene::findVariant).
std::string variantArgument(const py::object& variant) {
    if (variant.is_none()) {
        return {};
    }
    if (py::isinstance<py::int_>(variant) && !py::isinstance<py::bool_>(variant)) {
        return std::to_string(variant.cast<long long>());
    }
    if (py::isinstance<py::str>(variant)) {
        return variant.cast<std::string>();
    }
    throw py::type_error("variant must be None, a variant's name (str) or its index (int)");
}

// `size` is an int (square) or a (width, height) pair.
std::pair<std::uint32_t, std::uint32_t> imageSize(const py::object& size) {
    long width = 0;
    long height = 0;
    if (py::isinstance<py::int_>(size)) {
        width = height = size.cast<long>();
    } else {
        auto pair = size.cast<std::pair<long, long>>();
        width = pair.first;
        height = pair.second;
    }
    if (width < 1 || height < 1 || width > 8192 || height > 8192) {
        throw py::value_error("size must be an int or a (width, height) pair, each from 1 to 8192");
    }
    return {std::uint32_t(width), std::uint32_t(height)};
}

// The models a batch renders: a folder, list file or model path (what `encore batch` takes) or
// a sequence of (path, name) pairs (discover_inputs).
std::vector<batch::BatchInput> batchInputs(const py::object& inputs) {
    if (py::isinstance<py::str>(inputs) || py::hasattr(inputs, "__fspath__")) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(inputs));
        Result<std::vector<batch::BatchInput>> discovered =
            makeError(ErrorCode::InvalidArgument, "");
        {
            py::gil_scoped_release release;
            discovered = batch::discoverInputs(path);
        }
        return valueOrThrow(std::move(discovered));
    }
    std::vector<batch::BatchInput> listed;
    for (const py::handle item : inputs) {
        const auto [path, name] = item.cast<std::pair<std::string, std::string>>();
        if (name.empty()) {
            throw py::value_error("every input needs a non-empty output name");
        }
        listed.push_back({path, name});
    }
    return listed;
}

// discover_inputs: a folder, list file or model path, or a sequence of model paths.
py::list discoverInputs(const py::object& input) {
    std::vector<batch::BatchInput> inputs;
    if (py::isinstance<py::str>(input) || py::hasattr(input, "__fspath__")) {
        inputs = batchInputs(input);
    } else {
        std::vector<std::filesystem::path> paths;
        for (const py::handle item : input) {
            paths.emplace_back(
                py::str(py::module_::import("os").attr("fspath")(item)).cast<std::string>());
        }
        inputs = valueOrThrow(batch::listedInputs(paths));
    }
    py::list pairs;
    for (const batch::BatchInput& model : inputs) {
        pairs.append(py::make_tuple(model.path.string(), model.name));
    }
    return pairs;
}

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

class Renderer {
  public:
    Renderer(std::uint32_t samples,
             std::optional<std::size_t> device,
             const std::optional<std::string>& strategy)
        : mSamples(samples) {
        if (samples != 1 && samples != 4) {
            throw py::value_error("samples must be 1 or 4");
        }
        if (strategy) {
            mStrategy = render::strategyChoiceFromName(*strategy);
            if (!mStrategy) {
                std::string names;
                for (render::StrategyKind kind : render::allStrategies()) {
                    names += (names.empty() ? "" : ", ") + std::string(render::strategyName(kind));
                }
                throw py::value_error("strategy '" + *strategy +
                                      "' is not one of Encore's strategies (" + names +
                                      "; a direct one may take +bundle)");
            }
        }
        gpu::ContextOptions options;
        options.adapterIndex = device ? *device : deviceFromEnvironment();
        render::requestVisibilityFeatures(options);
        mContext = std::make_unique<gpu::Context>(valueOrThrow(gpu::Context::create(options)));
        mBatchRenderers = std::make_unique<batch::BatchRenderer>(*mContext);
    }

    Scene load(const std::string& path) {
        Result<scene::SceneData> loaded = makeError(ErrorCode::InvalidArgument, "");
        {
            py::gil_scoped_release release;
            loaded = scene::loadScene(path);
        }
        if (!loaded) {
            throw LoadError(loaded.error().message);
        }
        return Scene{std::make_shared<const scene::SceneData>(std::move(*loaded))};
    }

    py::object renderViews(const Scene& scene,
                           std::uint32_t views,
                           const py::object& size,
                           float elevation,
                           float distance,
                           std::optional<float> fov,
                           bool random,
                           std::uint64_t seed,
                           bool normalize,
                           bool normals,
                           bool depth,
                           const std::string& name,
                           const py::object& variantName,
                           const py::object& passes,
                           const std::string& segmentation,
                           const py::object& environment,
                           float intensity,
                           float rotation,
                           float exposure,
                           const std::string& toneMapping,
                           const std::string& background,
                           bool passFrames) {
        const auto [width, height] = imageSize(size);
        const ViewShading shading =
            viewShading(environment, intensity, rotation, exposure, toneMapping, background);
        std::vector<batch::ViewImage> kinds;
        if (!passes.is_none()) {
            if (normals || depth) {
                throw py::value_error(
                    "passes= replaces normals= and depth=: name \"normal\" and "
                    "\"depth\" among the passes.");
            }
            kinds = passKinds(passes);
            if (std::count(kinds.begin(), kinds.end(), batch::ViewImage::Segmentation) &&
                mSamples != 1) {
                throw py::value_error(
                    "The segmentation pass needs Renderer(samples=1): "
                    "multisampling would blend neighbouring objects' ids.");
            }
        }
        const batch::SegmentationBy by = segmentationBy(segmentation);
        const batch::ViewRigOptions rig = rigOptions(
            {views, elevation, py::float_(distance),
             fov ? py::object(py::float_(*fov)) : py::none(),
             random ? batch::CameraDistribution::Sphere : batch::CameraDistribution::Orbit, seed,
             normalize});
        const std::vector<batch::ViewCamera> cameraViews = batch::viewCameras(rig, name);
        std::optional<scene::VariantId> variant;
        if (const std::string chosen = variantArgument(variantName); !chosen.empty()) {
            auto found = scene::resolveVariant(*scene.data, chosen);
            if (!found) {
                throw py::value_error(found.error().message);
            }
            variant = *found;
        }
        Rendered rendered;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mMutex);  // Python threads may share a renderer.
            rendered = valueOrThrow(render(scene.data, variant, cameraViews, rig, width, height,
                                           normals, depth, shading, kinds, by, passFrames));
        }
        const auto rgbaArray = [&](const std::vector<image::ImageRgba8>& images) {
            py::array_t<std::uint8_t> pixels(
                {std::size_t(views), std::size_t(height), std::size_t(width), std::size_t(4)});
            std::uint8_t* out = pixels.mutable_data();
            for (const image::ImageRgba8& image : images) {
                std::memcpy(out, image.pixels.data(), image.pixels.size());
                out += image.pixels.size();
            }
            return pixels;
        };
        py::array_t<std::uint8_t> pixels = rgbaArray(rendered.color);
        const batch::PinholeIntrinsics pinhole =
            batch::intrinsicsFor(width, height, glm::radians(rig.horizontalFovDegrees.min));
        py::array_t<double> intrinsics({3, 3});
        auto k = intrinsics.mutable_unchecked<2>();
        const double values[3][3] = {{pinhole.focalX, 0.0, pinhole.centerX},
                                     {0.0, pinhole.focalY, pinhole.centerY},
                                     {0.0, 0.0, 1.0}};
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column) {
                k(row, column) = values[row][column];
            }
        }
        py::array_t<double> cameras({std::size_t(views), std::size_t(4), std::size_t(4)});
        auto c = cameras.mutable_unchecked<3>();
        for (std::size_t view = 0; view < cameraViews.size(); ++view) {
            const glm::mat4& cameraToWorld = cameraViews[view].cameraToWorld;
            for (int row = 0; row < 4; ++row) {
                for (int column = 0; column < 4; ++column) {
                    c(view, row, column) = cameraToWorld[column][row];  // glm: [column][row]
                }
            }
        }
        if (!passes.is_none()) {
            py::dict arrays;
            for (std::size_t i = 0; i < kinds.size(); ++i) {
                arrays[passName(kinds[i])] = passArray(kinds[i], rendered.passes[i], width, height);
            }
            arrays["intrinsics"] = intrinsics;
            arrays["cameras"] = cameras;
            return arrays;
        }
        py::list result;
        result.append(pixels);
        result.append(intrinsics);
        result.append(cameras);
        if (normals) {
            result.append(rgbaArray(rendered.normals));
        }
        if (depth) {
            // The 16-bit values of 000_depth.png times its depth_scale: distances along the
            // camera axis in the cameras' units, 0 where the pixel is mostly empty.
            const double scale = batch::depthScale(rig);
            py::array_t<float> distances(
                {std::size_t(views), std::size_t(height), std::size_t(width)});
            float* out = distances.mutable_data();
            for (const image::ImageGray16& image : rendered.depth) {
                for (const std::uint16_t steps : image.pixels) {
                    *out++ = float(double(steps) * scale);
                }
            }
            result.append(distances);
        }
        return py::tuple(result);
    }

    // Runs the job of `encore batch` on this renderer's device.
    py::dict runBatch(const py::object& inputs,
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
                      std::uint64_t shardSize) {
        batch::BatchOptions options;
        options.strategy = mStrategy;
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
        if (layout != "nerf" && layout != "objaverse") {
            throw py::value_error("layout must be \"nerf\" or \"objaverse\"");
        }
        options.layout =
            layout == "objaverse" ? batch::OutputLayout::Objaverse : batch::OutputLayout::Nerf;
        options.blankThreshold = blankThreshold;
        options.jobs = jobs;
        options.memoryLimitBytes = memoryLimitMiB << 20;
        options.strict = strict;
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

    std::string adapter() const { return mContext->adapterDescription().summary(); }
    std::size_t device() const { return mContext->adapterDescription().index; }
    batch::BatchRendererCounts batchCounts() {
        // Without the GIL while waiting: a batch on another thread takes it to report progress.
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);
        return mBatchRenderers->counts();
    }
    std::uint32_t samples() const { return mSamples; }
    // The strategy render_views and batch draw with: given, else each one's default.
    std::optional<std::string> strategy() const {
        return mStrategy ? std::optional(render::strategyChoiceName(*mStrategy)) : std::nullopt;
    }

  private:
    // The environment keywords of batch(): one file, or a folder's files drawn per model, and
    // the rotation ("random", degrees or a (min, max) pair) and intensity drawn per model.
    static void applyLighting(batch::BatchOptions& options,
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

    // A model's views, and its normal and depth images when asked for.
    struct Rendered {
        std::vector<image::ImageRgba8> color;
        std::vector<image::ImageRgba8> normals;
        std::vector<image::ImageGray16> depth;
        std::vector<PassImages> passes;  // With passes=: one per pass asked for, in order.
    };

    Result<Rendered> render(const std::shared_ptr<const scene::SceneData>& scene,
                            std::optional<scene::VariantId> variant,
                            const std::vector<batch::ViewCamera>& views,
                            const batch::ViewRigOptions& rig,
                            std::uint32_t width,
                            std::uint32_t height,
                            bool normals,
                            bool depth,
                            const ViewShading& shading,
                            std::span<const batch::ViewImage> kinds,
                            batch::SegmentationBy by,
                            bool passFrames) {
        const batch::StripLayout layout =
            batch::stripLayout(width, height, rig.views, mContext->limits());
        const render::StrategyChoice choice =
            mStrategy.value_or(render::StrategyChoice::of(render::StrategyKind::Bundles, false));
        // The passes that share the colour's camera are drawn in its render pass, as `encore
        // batch` draws them, unless pass_frames=True.
        batch::ExtraImages images;
        applyPassKinds(kinds, images);
        images.drawing = passFrames ? batch::PassDrawing::Frames : batch::PassDrawing::Targets;
        const render::PassTargets passTargets =
            batch::drawsPassTargets(images, choice.kind, mContext->limits())
                ? batch::passTargetsFor(by)
                : render::PassTargets::None;
        if (!mRenderer || mRenderer->target().width() != layout.targetWidth() ||
            mRenderer->target().height() != layout.height || mPassTargets != passTargets) {
            render::RendererOptions options;
            options.passTargets = passTargets;
            mPassTargets = passTargets;
            options.target = {layout.targetWidth(), layout.height, mSamples};
            options.toneMapping.background = render::BackgroundKind::Transparent;
            options.target.hdr = true;  // Whatever the background: depth and HDR read it.
            options.keepPipelines = true;
            mRenderer.reset();
            ENCORE_TRY_ASSIGN(auto created, render::Renderer::create(*mContext, options));
            mRenderer = std::make_unique<render::Renderer>(std::move(created));
            mPrepared.reset();
            mEnvironment.clear();  // A new renderer lights with the studio environment.
        }
        if (mPrepared != scene) {
            // The renderer refers to the scene it was given until the next prepare, even when
            // preparing failed: hold it that long.
            mPrepared.reset();
            mHeld = scene;
            ENCORE_TRY(mRenderer->prepare(*scene, choice.kind, choice.bundle));
            mPrepared = scene;
        }
        // Only material bindings change between variants: the prepared scene stays.
        ENCORE_TRY(mRenderer->selectVariant(variant));
        ENCORE_TRY(applyShading(*mRenderer, shading, mEnvironment));
        Rendered rendered;
        if (!kinds.empty()) {
            ENCORE_TRY_ASSIGN(rendered.passes, renderPasses(*mRenderer, scene->bounds, views, rig,
                                                            layout, kinds, by));
        }
        // With passes, the colour is its "rgba" pass.
        const bool colorPass = kinds.empty();
        if (colorPass) {
            ENCORE_TRY_ASSIGN(rendered.color,
                              batch::renderStrips(*mRenderer, scene->bounds, views, rig, layout));
        }
        if (normals) {
            ENCORE_TRY_ASSIGN(rendered.normals,
                              batch::renderStrips(*mRenderer, scene->bounds, views, rig, layout,
                                                  batch::ViewImage::Normal));
        }
        if (depth) {
            ENCORE_TRY_ASSIGN(rendered.depth, batch::renderDepthStrips(*mRenderer, scene->bounds,
                                                                       views, rig, layout));
        }
        ENCORE_TRY(mContext->checkNoErrors("Rendering '" + scene->sourcePath.string() + "'"));
        return rendered;
    }

    std::uint32_t mSamples;
    std::optional<render::StrategyChoice> mStrategy;
    std::unique_ptr<gpu::Context> mContext;
    std::unique_ptr<render::Renderer> mRenderer;  // After mContext: destroyed before it.
    render::PassTargets mPassTargets = render::PassTargets::None;  // mRenderer's.
    std::unique_ptr<batch::BatchRenderer> mBatchRenderers;         // Kept by batch() between calls.
    std::shared_ptr<const scene::SceneData> mHeld;                 // Last given to prepare().
    std::shared_ptr<const scene::SceneData> mPrepared;             // Prepared successfully.
    std::string mEnvironment;  // The .hdr the renderer lights with; empty: the studio one.
    std::mutex mMutex;
};

}  // namespace
}  // namespace encore::python

PYBIND11_MODULE(_encore, module) {
    using namespace encore::python;
    module.doc() = "Encore: glTF 2.0 rendering with WebGPU (Dawn), for datasets of rendered views.";
    static py::exception<EncoreError> error(module, "Error", PyExc_RuntimeError);
    static py::exception<LoadError> loadError(module, "LoadError", error.ptr());
    py::register_exception_translator([](std::exception_ptr pointer) {
        try {
            if (pointer) {
                std::rethrow_exception(pointer);
            }
        } catch (const LoadError& caught) {
            PyErr_SetString(loadError.ptr(), caught.what());
        } catch (const EncoreError& caught) {
            PyErr_SetString(error.ptr(), caught.what());
        }
    });

    py::class_<Scene>(module, "Scene", "A loaded glTF model (renderer.load).")
        .def_property_readonly("path",
                               [](const Scene& scene) { return scene.data->sourcePath.string(); })
        .def_property_readonly("bounds",
                               [](const Scene& scene) {
                                   const auto& bounds = scene.data->bounds;
                                   return py::make_tuple(
                                       py::make_tuple(bounds.min.x, bounds.min.y, bounds.min.z),
                                       py::make_tuple(bounds.max.x, bounds.max.y, bounds.max.z));
                               })
        .def_property_readonly(
            "variants", [](const Scene& scene) { return scene.data->variants; },
            "The names of the model's KHR_materials_variants variants, by index (render_views' "
            "and batch's variant=); empty without the extension.");

    py::class_<Renderer>(module, "Renderer",
                         "One GPU device (Vulkan) rendering models from a view rig.")
        .def(py::init<std::uint32_t, std::optional<std::size_t>,
                      const std::optional<std::string>&>(),
             py::arg("samples") = 4, py::arg("device") = py::none(),
             py::arg("strategy") = py::none(),
             "A renderer on adapter `device` of encore.adapters() (default: the ENCORE_DEVICE "
             "environment variable, else 0, the adapter Dawn prefers), drawing with `strategy` "
             "(a name of `encore --help`'s list, e.g. \"visibility\" or \"gpu-culling-bundles\"; "
             "default: render_views draws with bundles, batch with its default).")
        .def("load", &Renderer::load, py::arg("path"),
             "Loads a .gltf or .glb file; raises encore.LoadError with the loader's message.")
        .def("render_views", &Renderer::renderViews, py::arg("scene"), py::arg("views") = 12,
             py::arg("size") = 512, py::arg("elevation") = 30.0f, py::arg("distance") = 1.5f,
             py::arg("fov") = py::none(), py::arg("random") = false, py::arg("seed") = 0,
             py::arg("normalize") = true, py::arg("normals") = false, py::arg("depth") = false,
             py::arg("name") = "", py::arg("variant") = py::none(), py::arg("passes") = py::none(),
             py::arg("segmentation_by") = "node", py::arg("environment") = py::none(),
             py::arg("environment_intensity") = 1.0f, py::arg("environment_rotation") = 0.0f,
             py::arg("exposure") = 1.0f, py::arg("tone_mapping") = "neutral",
             py::arg("background") = "transparent", py::arg("pass_frames") = false,
             "Renders `views` RGBA views (straight alpha, transparent background) of the scene "
             "normalised into a unit box, from an orbit `elevation` degrees above the horizon or "
             "(random=True) directions uniform on the sphere drawn from `seed` (and, as `encore "
             "batch` "
             "draws them, the model's output `name`). Returns (images "
             "uint8 (N, H, W, 4), intrinsics float64 (3, 3) in pixels, camera-to-world float64 "
             "(N, 4, 4) with OpenGL camera axes), as `encore batch` writes them. `fov` is "
             "horizontal, in degrees (default: a 35 mm lens on a 32 mm sensor). normals=True "
             "appends the world-space normals, uint8 (N, H, W, 4) as n * 0.5 + 0.5 with the "
             "views' alpha, and depth=True (after them) the distances along each camera's axis, "
             "float32 (N, H, W), 0 where less than half of a pixel is covered: the pixels of "
             "`encore batch --normals --depth`'s 000_normal.png and of 000_depth.png times its "
             "depth_scale. variant= draws a KHR_materials_variants variant (its name or index, "
             "scene.variants lists them; ValueError for one the model lacks) instead of the "
             "default materials. passes=(\"rgba\", \"albedo\", \"normal\", \"material\", "
             "\"segmentation\", \"depth\", \"hdr\") (any of them, in any order) returns a dict "
             "instead: each pass's array (uint8 (N, H, W, 4) for rgba, albedo, normal and "
             "material; depth float32 (N, H, W) along the camera axis, inf where empty; "
             "segmentation uint16 (N, H, W), 1 + the node (segmentation_by=\"mesh\", "
             "\"material\") index, needing samples=1; hdr float32 (N, H, W, 4), linear and "
             "premultiplied) with \"intrinsics\" and \"cameras\", as `encore batch` writes "
             "them (docs/batch.md#passes); they are drawn in the colour's render pass, or with "
             "pass_frames=True one frame per pass (the same values, slower). Shading as `encore "
             "render`'s: environment (an .hdr "
             "file), environment_intensity, environment_rotation (degrees), exposure, "
             "tone_mapping (neutral, aces, none), background (transparent, env, #rrggbb). The GIL "
             "is released while rendering.")
        .def(
            "batch", &Renderer::runBatch, py::arg("inputs"), py::arg("output"),
            py::arg("views") = 12, py::arg("random_views") = 0, py::arg("seed") = 0,
            py::arg("elevation") = 30.0f, py::arg("distance") = 1.5f, py::arg("fov") = py::none(),
            py::arg("normalize") = true, py::arg("size") = 512, py::arg("samples") = py::none(),
            py::arg("jobs") = 0, py::arg("memory_limit_mib") = 2048, py::arg("strict") = false,
            py::arg("normals") = false, py::arg("depth") = false, py::arg("top_light") = 0.0f,
            py::arg("png_compression") = "small", py::arg("failure_log") = true,
            py::arg("renderers") = encore::batch::BatchOptions{}.renderers,
            py::arg("lod_error") = 0.0f, py::arg("camera_distribution") = "orbit",
            py::arg("camera_jitter") = 0.0f, py::arg("environment") = py::none(),
            py::arg("environment_dir") = py::none(), py::arg("environment_rotation") = py::none(),
            py::arg("environment_intensity") = py::none(), py::arg("layout") = "nerf",
            py::arg("blank_threshold") = encore::batch::kDefaultBlankThreshold,
            py::arg("variant") = py::none(), py::arg("variants") = py::none(),
            py::arg("passes") = py::none(), py::arg("segmentation_by") = "node",
            py::arg("depth_format") = "png", py::arg("model_timeout") = 0.0,
            py::arg("max_texture_size") = encore::batch::kDefaultMaxTextureSize,
            py::arg("shards") = 0, py::arg("shard_size") = 0,
            "Runs the job of `encore batch` on this renderer's device: `inputs` is what the "
            "command takes (folder, list file, model) or (path, name) pairs from "
            "discover_inputs. Returns the summary (models rendered, failed, skipped; views; "
            "seconds; time per stage; failures). Failed models are also written to "
            "OUTPUT/failures.jsonl unless failure_log=False. `samples` defaults to the "
            "renderer's. lod_error > 0 draws each instance at the coarsest level of detail "
            "whose error stays under that many pixels in the nearest view (`encore batch "
            "--lod-error`). As the command's options: camera_distribution (\"orbit\", "
            "\"sphere\", \"upper-hemisphere\"), camera_jitter (degrees), distance and fov (a "
            "number or a (min, max) pair drawn per view), environment (an .hdr), environment_dir "
            "(a folder of .hdr, one drawn per model), environment_rotation (degrees, a pair or "
            "\"random\") and environment_intensity (a number or a pair) drawn per model, layout "
            "(\"nerf\" or \"objaverse\": a .npy camera matrix per view) and blank_threshold "
            "(pixels). variant= (a name or index) draws every model in that KHR_materials_variants "
            "variant into OUTPUT/<name>@<variant> (`encore batch --variant`); variants=\"all\" "
            "also draws each model in every variant, each a sample of its own (`--variants all`). "
            "passes= names the images beside the colour ones as render_views does (\"normal\", "
            "\"depth\", \"albedo\", \"material\", \"segmentation\", \"hdr\"; `--albedo` ...), "
            "with segmentation_by (node, mesh, material) and depth_format (png, exr). "
            "model_timeout (seconds, 0: none) abandons a model still loading or drawing after "
            "that long (stage \"timeout\", `--model-timeout`); max_texture_size downscales "
            "larger images while loading (`--max-texture-size`, 0: none). shards=N or "
            "shard_size=BYTES writes WebDataset .tar shards instead of folders (`--shards`, "
            "`--shard-size`). "
            "The GIL is released while it runs.")
        .def_property_readonly("samples",
                               [](const Renderer& renderer) { return renderer.samples(); })
        .def_property_readonly("adapter", &Renderer::adapter)
        .def_property_readonly("strategy", &Renderer::strategy,
                               "The strategy given to the constructor, or None.")
        .def_property_readonly("device", &Renderer::device,
                               "The index of the renderer's adapter in encore.adapters().")
        .def_property_readonly(
            "batch_renderers_created",
            [](Renderer& renderer) { return renderer.batchCounts().renderers; },
            "How many times batch() built its renderer (render target, pipelines): once for "
            "calls with the same size, samples and normals/depth, again when those change.")
        .def_property_readonly(
            "batch_environments_created",
            [](Renderer& renderer) { return renderer.batchCounts().environments; },
            "How many times batch() computed the environment maps: once for every call so far.");

    module.def(
        "adapters",
        [] {
            py::list list;
            for (const encore::gpu::AdapterDescription& adapter :
                 valueOrThrow(encore::gpu::listAdapters())) {
                py::dict entry;
                entry["index"] = adapter.index;
                entry["name"] = adapter.name;
                entry["type"] = encore::gpu::adapterTypeName(adapter.adapterType);
                entry["backend"] = encore::gpu::backendName(adapter.backend);
                entry["driver"] = adapter.driver;
                entry["summary"] = adapter.summary();
                list.append(entry);
            }
            return list;
        },
        "The GPU adapters, as `encore info` lists them: dicts of index, name, type ('discrete "
        "GPU', 'CPU', ...), backend, driver and summary. Renderer(device=index) picks one.");
    module.def("discover_inputs", &discoverInputs, py::arg("input"),
               "The models `encore batch INPUT` renders, as (path, output name) pairs: INPUT is a "
               "folder (searched recursively), a list file (one path per line, or a JSON array), "
               "a model, or a sequence of model paths (named relative to the deepest folder that "
               "holds them all).");
}
