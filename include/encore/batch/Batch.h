#pragma once

// Renders collections of glTF models from fixed or random viewpoints into a dataset folder:
// for each model OUT/<name>/000.png ... (RGBA, straight alpha, transparent background by
// default) and OUT/<name>/transforms.json (TransformsJson.h), on one device or several.
//
// It is a pipeline, not a loop: models are parsed and their images decoded on a thread pool
// ahead of the GPU (as far as BatchOptions::memoryLimitBytes allows), several renderers take
// the models in turn so that the next model uploads while the GPU draws the previous ones
// (BatchOptions::renderers), the views of a model are drawn side by side into one wide target
// (Renderer::renderViews) and read back through a ring of staging buffers with mapAsync, and
// PNG encoding runs on the pool while the GPU goes on. With several devices, each has its own
// device thread and renderers (DeviceLane.h); they share the pool, the output folder and the
// failure log, and each takes whichever model has loaded next.
//
// Nothing is lost and nothing half-written (ModelOutput.h): finished models are skipped, so a
// run stopped at any moment resumes where it stopped. Bad input never stops the batch: a model
// that fails is listed in OUT/failures.jsonl (Failure below) and the batch goes on.
//
// Each model also gets OUT/<name>/metadata.json (what the file holds, its SHA-256, the views
// that came out blank, timings), and with OutputLayout::Objaverse a camera matrix per view as
// NumPy's 000.npy. Cameras and lighting may vary from view to view and model to model
// (ViewRig.h, BatchLighting.h), drawn from the seed and the model's name: every frame of
// transforms.json records its own intrinsics and lighting.
//
// Files that would stop it do not: a model reads only files inside its folder (allowUrisOutside),
// a model past BatchOptions::modelTimeoutSeconds is abandoned (stage "timeout"), one holding more
// than memoryLimitBytes decoded fails, images larger than maxTextureSize are downscaled while
// loading, and a device
// lost mid-batch is created again, the models it had in flight drawn again once. With `shards`
// or `shardBytes` the samples go into WebDataset .tar shards instead of folders (docs/batch.md).

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "encore/batch/BatchInputs.h"
#include "encore/batch/BatchLighting.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Renderer.h"

namespace encore::batch {

// Renderers kept on one device from one run to the next (src/batch/BatchRenderer.h): the
// command line and the Python module keep them; the overloads below that take them serve those.
class BatchRenderer;

// Where the time went, in seconds. Load and encode run on the pool: their times add up the
// threads' work (they may exceed the wall time). The others are the device thread's and add up
// to at most the wall time; the GPU works beside them, so its own time is not among them.
// A model that failed, as failures.jsonl lists it: the file, the stage (load, render, write ...)
// and the error.
struct Failure {
    std::filesystem::path file;
    std::string stage;
    std::string error;
};

// The GPU's time in one stage, summed over the batch's timed passes or commands.
struct GpuStageTime {
    double milliseconds = 0.0;
    std::uint64_t timed = 0;    // Passes (or command ranges) counted.
    std::uint64_t untimed = 0;  // Left untimed because the query set was full before a flush.
};

struct StageTimes {
    double load = 0.0;  // Parsing the file and decoding its images.
    // Renderer::prepare (buffers, textures, pipelines, bundles) and, before it, creating the
    // staging buffers that the pool copies the model's images into (`staging`).
    double upload = 0.0;
    double staging = 0.0;
    double render = 0.0;  // Recording and submitting the views.
    // The device thread waiting for the GPU to finish views and their copies: what the GPU's
    // work exceeds the uploads and recording it overlaps with.
    double gpu = 0.0;
    double readback = 0.0;  // Unpacking the mapped rows into images.
    double encode = 0.0;    // PNG encoding and writing the files.
    // The CPU time of the load and encode work (the threads' CPU clocks): on a host with more
    // pool threads than free cores, load and encode also count the time a thread waited for a
    // core; these do not, so they say which stage's work fills the cores.
    double loadCpu = 0.0;
    double encodeCpu = 0.0;
    // The upload's parts (Renderer::prepare's own breakdown, milliseconds summed over models).
    render::PrepareTimes uploadParts;
    // The GPU's own time by render::GpuStage, from timestamps (BatchOptions::gpuTimestamps);
    // empty when not asked for or the device has no timestamp queries.
    std::vector<GpuStageTime> gpuStages;
};

struct BatchProgress {
    std::size_t total = 0;     // Models in the batch.
    std::size_t rendered = 0;  // Finished by this run (every file written).
    std::size_t failed = 0;    // Listed in failures.jsonl.
    std::size_t skipped = 0;   // Finished by an earlier run.
    std::uint64_t views = 0;   // Images written by this run.
    double seconds = 0.0;      // Since the batch started.

    std::size_t done() const { return rendered + failed + skipped; }
};

// What one device of a batch did.
struct DeviceSummary {
    std::string adapter;       // gpu::AdapterDescription::summary().
    std::size_t device = 0;    // Its index (gpu::listAdapters).
    std::uint64_t models = 0;  // Models it uploaded (failed ones too).
    std::uint64_t views = 0;   // Views it drew.
    // Its passes were drawn in the colour frame's render pass (PassDrawing::Targets), not one
    // frame per pass.
    bool passTargets = false;
    // Its PNG rows were filtered on the GPU (BatchOptions::pngFiltering).
    bool pngRowsOnGpu = false;
    // What its thread created in the driver (metadata.json's `gpu`, summed): GPU objects that
    // hold memory and bytes of mappable buffers, over the run (its renderers and pools too), and
    // how many models created any.
    std::uint64_t gpuObjectsCreated = 0;
    std::uint64_t gpuBytesMapped = 0;
    std::uint64_t modelsCreatingGpuObjects = 0;
};

struct BatchSummary : BatchProgress {
    bool interrupted = false;  // BatchOptions::stop was set: models were left unrendered.
    // Loads that did not stop when cancelled (stuck in the kernel: a hung mount), left to their
    // threads when the batch ended; their models failed as timeouts or were left unrendered.
    std::size_t loadsLeftBehind = 0;
    // The device threads' stages are summed over the devices (with several, the sums may exceed
    // the wall time).
    StageTimes stages;
    std::vector<DeviceSummary> devices;  // One per device, in the order they were given.
    std::vector<Failure> failures;       // As failures.jsonl lists them.
};

// Four: on the H100 at 4x multisampling, three left the device thread waiting for the GPU
// behind models whose GPU and upload times differ (797 against 898 views per second).
inline constexpr std::size_t kDefaultRenderers = 4;
// BatchOptions::renderers lies in 1..kMaxRenderers: each holds a scene and a render target on
// the device, and past a few they only add memory (the queue ahead of the GPU is deep enough).
inline constexpr std::size_t kMaxRenderers = 8;

// What a model's folder holds besides its images, transforms.json and metadata.json.
enum class OutputLayout {
    Nerf,       // Nothing more: transforms.json describes the cameras.
    Objaverse,  // A 000.npy beside each 000.png: the camera as the Objaverse-XL scripts save it
                // (ObjaverseCamera.h).
    // A 000.json beside each 000.png: the camera as G-Objaverse's files hold it (origin, the
    // camera's x, y and z axes in the world, x_fov and y_fov in radians; CameraConvention.h,
    // cameraFileJson), in OpenCV's axes unless BatchOptions::cameraConvention says otherwise.
    Gobjaverse,
};

// Where the views' PNG rows are filtered and the passes' samples made from what the GPU drew
// (BatchOptions::pngFiltering): the PNG files are the same either way (depth within one step).
enum class PngFiltering {
    Auto,  // On the GPU, unless the adapter is a CPU (lavapipe: its "GPU" is the pool's cores).
    Gpu,   // A compute pass writes the rows ready to compress (PngRowsPass.h).
    Cpu,   // The pool crops, converts and filters the read-back.
};

// BatchOptions::maxTextureSize: what GPUs sample fast and datasets' 512-pixel views never
// resolve beyond.
inline constexpr std::uint32_t kDefaultMaxTextureSize = 4096;

// BatchOptions::visibilityFromTriangles's default at four samples. On one H200, generated models
// of 104,000 to 1.59 M triangles were drawn 1.2x to 3.4x faster by the visibility strategy; the
// ten shared models as a whole 1.37x faster with the three above 100,000 triangles drawn by it,
// 1.33x with only the largest (1.04 M), slower with all ten (docs/batch.md, Strategies).
inline constexpr std::uint64_t kAutoVisibilityTriangles = 100'000;
// Its default at one sample, where the graphics pipeline's raster costs a quarter as much and
// the batch waits on its loaders' CPU, which a model's clusters add to: on one H200 visibility
// was 0.71x bundles at 104,000 triangles, 1.02x at 404,000, 1.44x at 802,000, 1.96x at 1.59 M.
inline constexpr std::uint64_t kAutoVisibilityTrianglesOneSample = 500'000;
// At four samples auto also draws with visibility each model whose primitives its compute raster
// takes all of (opaque, static triangle lists: scene::SceneData::drawsOnlyOpaqueStaticTriangles),
// whatever its size: on one H200 that took 0.2-0.9x the GPU time of bundles for each such model of
// the ten shared ones, while a model with blended or masked parts (drawn by the graphics pipeline
// beside the compute raster) took 1.5x (docs/benchmarks/2026-11-29-h200-decode-floor.md). An
// explicit BatchOptions::visibilityFromTriangles replaces this rule.
inline constexpr bool kAutoVisibilityOpaqueStatic = true;
// The line for `samples` (1 or 4).
constexpr std::uint64_t autoVisibilityTriangles(std::uint32_t samples) {
    return samples == 1 ? kAutoVisibilityTrianglesOneSample : kAutoVisibilityTriangles;
}

// BatchOptions::modelTimeoutSeconds's default: far above what a model takes (the first model's
// upload compiles the pipelines: seconds on lavapipe), so that no file holds a batch for ever.
inline constexpr double kDefaultModelTimeoutSeconds = 600.0;

// Fewer covered pixels than this make a view blank (BatchOptions::blankThreshold).
inline constexpr std::uint32_t kDefaultBlankThreshold = 1;

struct BatchOptions {
    std::filesystem::path output;
    std::uint32_t width = 512;
    std::uint32_t height = 512;
    std::uint32_t samples = 4;  // 1 or 4.
    ViewRigOptions views;
    // An environment, rotation and intensity per model (drawn from views.seed), applied over
    // `renderer`'s lighting.
    LightingVariation lighting;
    OutputLayout layout = OutputLayout::Nerf;
    // The axes of every written camera (transforms.json's transform_matrix, the .npy matrices,
    // the camera files), recorded in transforms.json and metadata.json. Unset: each file's own:
    // transforms.json in OpenGL's (NeRF's), the .npy matrices in Blender's (the Objaverse
    // scripts'), the camera files in OpenCV's (G-Objaverse's).
    std::optional<CameraConvention> cameraConvention;
    // The preset (BatchPresets.h) the options started from, recorded in metadata.json; empty:
    // none.
    std::string preset;
    // WebDataset shards instead of a folder per model (ShardWriter.h): OUT/shard-000000.tar ...
    // holding each sample's files as `<name>.000.png`, `<name>.transforms.json`, ... `shards`:
    // about that many shards (each holds the models of the batch divided by it); `shardBytes`:
    // a shard is finished once it holds that many bytes. 0 and 0: a folder per model.
    std::uint32_t shards = 0;
    std::uint64_t shardBytes = 0;
    // A view whose colour image has fewer pixels with non-zero alpha than this is blank: listed
    // in metadata.json's blankViews, and with `strict` the model fails (stage "blank"). Coverage
    // is counted with a transparent background only (the default); with another background no
    // view is blank. 0: none is.
    std::uint32_t blankThreshold = kDefaultBlankThreshold;
    // Lighting, tone mapping and background; the target is set from width, height and samples.
    render::RendererOptions renderer = [] {
        render::RendererOptions options;
        options.toneMapping.background = render::BackgroundKind::Transparent;
        return options;
    }();
    // Every model drawn with this strategy. Unset: chosen per model (chooseStrategyPerModel),
    // else bundles, as `encore render` draws, or gpu-culling-bundles with levels of detail
    // (lodErrorPixels > 0), which chooses the levels.
    std::optional<render::StrategyChoice> strategy;
    // `--strategy auto`, the default: with `strategy` unset, each model's strategy is chosen from
    // what it holds and recorded in its metadata.json: visibility (compute raster) for a model
    // that draws at least `visibilityFromTriangles` triangles on a GPU, else the default above,
    // which draws every model on a CPU adapter (lavapipe), on a device without the visibility
    // feature, and with extra images (normals, depth, ...). Both strategies' files are the same
    // byte for byte from run to run (docs/batch.md, Strategies). False: the default above.
    bool chooseStrategyPerModel = true;
    // With chooseStrategyPerModel: the triangles (at full detail, summed over the model's
    // instances) from which a model is drawn with the visibility strategy. Unset:
    // autoVisibilityTriangles(samples) on GPUs, never on a CPU adapter; set, on any adapter with
    // the feature.
    std::optional<std::uint64_t> visibilityFromTriangles;
    // > 0: models load with levels of detail (scene::LoadOptions::buildLevelsOfDetail) and each
    // instance is drawn at the coarsest level whose simplification error, projected in the
    // nearest view, stays under this many pixels. Needs a gpu-culling strategy or visibility,
    // whose cull chooses the levels. Building the levels costs load time (0.65 s of CPU for the ten
    // shared models, most of it a sphere grid of a million triangles): it pays where the GPU draws
    // more triangles than the views can show, as on lavapipe. 0: full detail (the default).
    float lodErrorPixels = 0.0f;

    bool strict = false;  // Loader warnings and blank views fail the model.
    // Models may read buffers and images outside their own folder
    // (scene::LoadOptions::allowUrisOutside): for trusted local trees only.
    bool allowUrisOutside = false;
    // > 0: a model still loading, uploading or drawing after this many seconds of work on it
    // (waiting in the queue between them does not count) is abandoned: a line in failures.jsonl
    // with stage "timeout", and the batch goes on. A load is told to stop (its thread finishes
    // at its loader's next check, its result dropped; a thread stuck in the kernel is left
    // behind when the batch ends); views already on the GPU are read back and dropped. A GPU
    // that hangs inside a draw is the driver's to reset (a device loss). 0: no limit.
    double modelTimeoutSeconds = kDefaultModelTimeoutSeconds;
    // Images with a side longer than this are downscaled while loading (JPEGs decode at a
    // fraction of their size), listed in metadata.json's imagesDownscaled. 0: kept as they are.
    std::uint32_t maxTextureSize = kDefaultMaxTextureSize;
    // KHR_materials_variants. A name or index: every model drawn in that variant only, into
    // OUT/<name>@<variant> (variantSampleNames); a model without it fails at "load". Empty: the
    // default materials, into OUT/<name>.
    std::string variant;
    // Every model drawn with its default materials into OUT/<name> and in each of its variants
    // into OUT/<name>@<variant>, each a sample of its own (finished, resumed and written as a
    // model is) from one upload: only the material bindings change between them. A model counts
    // once in BatchProgress, rendered when all its samples are. Excludes `variant`.
    bool allVariants = false;
    // Whether OUT/failures.jsonl is written (and emptied first). Off, the failures are only in
    // the summary: for callers that run several batches into one folder at once and write one
    // log of them all (encore.dask), where each run would empty the others' log.
    bool writeFailureLog = true;
    // Also write each view's world-space normals ("000_normal.png") and 16-bit depth
    // ("000_depth.png", its scale in transforms.json): one more frame per view and image,
    // through the renderer's normal and depth debug channels without tone mapping.
    ExtraImages images;
    // > 0: also write OUT/<name>/points.ply, this many points drawn uniformly by area from the
    // model's triangles in the normalised frame, with normals and base colours (PointCloud.h),
    // drawn from views.seed and the model's name. 0: none.
    std::uint32_t pointCloudPoints = 0;
    // Lux of a directional light shining straight down (-Y) added to every model beside the
    // environment, as the dataset scripts light objects from above; 0: none.
    float topLightLux = 0.0f;
    // Small: libdeflate's matches (the default). Fast: runs only, about 2.4 times faster for
    // files about 16% larger, for when encoding limits the batch (image::PngCompression).
    image::PngCompression pngCompression = image::PngCompression::Small;
    PngFiltering pngFiltering = PngFiltering::Auto;
    std::size_t jobs = 0;  // Pool threads; 0: one per hardware thread.
    // Bytes the models hold decoded at once, at most: the scenes loaded ahead and the loads in
    // progress (a load past it waits unless it is the oldest); a model alone past it fails.
    std::uint64_t memoryLimitBytes = std::uint64_t{2} << 30;
    // Read-backs in flight or still being cropped by the pool: one more than the default
    // renderers, so that a read whose strips are being cropped does not hold up the next.
    std::size_t readbackSlots = kDefaultRenderers + 1;
    // Renderers that take the models in turn, each holding one model's scene on the device:
    // with N, the device thread uploads a model while the GPU may still draw the N - 1 before
    // it. 1: each model is uploaded only once the previous model's views are read back (the
    // sequential pipeline). More smooths out models whose upload and drawing times differ, at
    // the cost of one more scene and render target in GPU memory each. 1..kMaxRenderers.
    std::size_t renderers = kDefaultRenderers;
    // Time the GPU's stages with timestamp queries (StageTimes::gpuStages), when the context's
    // device has them (gpu::ContextOptions::timestamps). A few queries per pass; nothing waits.
    bool gpuTimestamps = false;
    // Set (from a signal handler, another thread) to stop starting models: views in flight are
    // still written, and runBatch returns with `interrupted`.
    const std::atomic<bool>* stop = nullptr;
    // Called on the calling thread as models finish.
    std::function<void(const BatchProgress&)> progress;
};

// Runs the batch on `context`. Fails only when the batch cannot run at all (the output folder
// cannot be created, the options are invalid, the renderer cannot be created); a model's failure
// is in failures.jsonl and the summary.
Result<BatchSummary> runBatch(gpu::Context& context,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options);
// The same on the device of `renderers`, with the renderer it kept from an earlier run when the
// options allow; what this run builds is kept in it for the next. The images
// are the same either way.
Result<BatchSummary> runBatch(BatchRenderer& renderers,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options);
// The same on several devices at once, each BatchRenderer on its own context (device): a device
// thread each, one pool, one output folder. Every model is rendered once, by whichever device
// is free, and its files are byte for byte those one device writes (on devices of one kind:
// two drivers may round differently). Fails when a device's renderers cannot be created.
Result<BatchSummary> runBatch(std::span<BatchRenderer* const> devices,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options);

}  // namespace encore::batch
