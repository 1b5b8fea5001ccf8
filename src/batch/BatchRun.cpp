#include "encore/batch/Batch.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "batch/BatchOptionsValidation.h"
#include "batch/ModelLoader.h"
#include "batch/ModelOutput.h"
#include "batch/ModelPlan.h"
#include "batch/ModelWriter.h"
#include "batch/ViewStrips.h"
#include "core/Elapsed.h"
#include "core/ThreadPool.h"
#include "encore/batch/BatchRenderer.h"
#include "encore/batch/FailureLog.h"
#include "encore/gpu/StageTimestamps.h"
#include "encore/gpu/TextureReadbackRing.h"
#include "gpu/StagingBuffers.h"
#include "render/StagedImages.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

Error lostWhileDrawing() {
    return makeError(ErrorCode::DeviceError,
                     "The GPU device was lost while the model's views were drawn.");
}

Error deviceNotRecreated() {
    return makeError(ErrorCode::DeviceError,
                     "The GPU device was lost and could not be created again.");
}

// The pool runs at a lower priority than the device thread: with a thread per core loading and
// encoding, the device thread (uploads, recording, read-back, the GPU's only feeder) otherwise
// waits for a core behind them while the GPU runs dry.
constexpr int kPoolNiceness = 10;

// Views [first, first + count) of a model, drawn side by side in one read-back (ViewStrips.h).
struct ChunkInFlight {
    std::shared_ptr<ModelJob> job;
    std::size_t renderer = 0;  // Which of BatchRun's renderers drew them.
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    ViewImage kind = ViewImage::Color;
};

// A directional light shining straight down, placed by no node.
void addTopLight(scene::SceneData& scene, float lux) {
    scene::Light light;
    light.name = "encore batch top light";
    light.type = scene::LightType::Directional;
    light.intensity = lux;
    scene::LightInstance placed;
    placed.light = scene::LightId(scene.lights.size());
    placed.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    scene.lights.push_back(light);
    scene.lightInstances.push_back(placed);
}

// One of the renderers that take models in turn, and the scene it last prepared: the renderer
// refers to that scene (and the loader's bytes behind it) until it prepares the next one.
struct RendererSlot {
    render::Renderer* renderer = nullptr;  // Owned by the run's BatchRenderer.
    std::optional<LoadedModel> prepared;
};

// The views of a model that one target holds: [first, first + count), drawn with `cameras`.
struct TargetViews {
    std::shared_ptr<ModelJob> job;
    std::size_t renderer = 0;  // An index into BatchRun::mRenderers.
    std::span<const render::Camera> cameras;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

class BatchRun {
  public:
    BatchRun(BatchRenderer& renderers,
             std::span<const BatchInput> inputs,
             const BatchOptions& options)
        : mContext(renderers.context()),
          mBatchRenderer(renderers),
          mInputs(inputs),
          mOptions(options),
          mStrategy(batchStrategy(options)),
          mPool(options.jobs, kPoolNiceness) {}

    Result<BatchSummary> run();

  private:
    // Creates the renderers (and the read-back ring) on the context's device, one environment
    // for them all, with the stage timestamps when asked for.
    Result<void> createRenderers();
    // Ends the stage timestamps of the current device (lost, or at the run's end), adding what
    // they measured to mGpuStageTotals, and detaches them from the renderers.
    void finishTimestamps();
    // Waits until the GPU is done with what renderer `slot` drew last, handing those views to
    // the encoders, so that it may prepare its next scene without waiting for the others.
    void collectRenderer(std::size_t slot);
    // Frees renderer `slot`'s scene and gives its bytes back to the loader.
    void releasePrepared(RendererSlot& slot);
    bool stopRequested() const { return mOptions.stop && mOptions.stop->load(); }
    void renderModel(LoadedModel& loaded);
    // Takes the oldest read-back and hands its views to the pool.
    void collectOldest();
    void collectReady();
    // Draws the views through `channel` with tone mapping off, then shades again.
    void renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                            render::Renderer& renderer,
                            render::DebugChannel channel,
                            const std::function<void()>& draw);
    // Draws a target's views through the depth channel and reads them back now.
    void renderDepth(const TargetViews& views, float unitsPerModelUnit, double& waiting);
    // Draws a target's views and starts reading them back; `waiting` adds the time spent
    // waiting for a free read-back slot.
    void renderChunk(const TargetViews& views, ViewImage kind, double& waiting);
    // After a failure: a lost device is replaced, and the renderer with it.
    void recoverIfLost();
    void reportProgress(bool force);
    BatchProgress progress() const;

    gpu::Context& mContext;
    // Owns the renderer and the read-back ring, which may outlive this run (BatchRenderer.h).
    BatchRenderer& mBatchRenderer;
    std::span<const BatchInput> mInputs;
    std::vector<BatchInput> mPending;  // Not finished by an earlier run, in load order.
    const BatchOptions& mOptions;
    const render::StrategyChoice mStrategy;  // BatchOptions::strategy, or its default.
    ThreadPool mPool;
    Clock::time_point mStart = Clock::now();
    std::optional<FailureLog> mFailures;
    SharedCounters mCounters;
    // Writes to mFailures: made with it, by run().
    std::optional<ModelWriter> mWriter;
    std::optional<ModelPlanner> mPlanner;  // Made by run().
    StageTimes mGpuStages;                 // The device thread's stages.
    std::size_t mSkipped = 0;
    StripLayout mLayout;
    // Models go to the renderers in turn: while the GPU draws model k with one, the device
    // thread uploads model k + 1 with another (BatchOptions::renderers). The renderers and the
    // ring belong to mBatchRenderer, which may keep them for later runs; no renderer is left
    // after a device loss that could not be recovered.
    std::vector<RendererSlot> mRenderers;
    std::uint64_t mModelsPrepared = 0;  // Models handed to a renderer: picks the next one.
    // Device losses so far: a renderer used across a collectOldest() may have been replaced.
    std::uint64_t mDevicesLost = 0;
    gpu::TextureReadbackRing* mRing = nullptr;
    // The staging buffers of the models' images, on the current device, reused from model to
    // model.
    std::shared_ptr<gpu::StagingBuffers> mStaging;
    // With BatchOptions::gpuTimestamps: on the current device, flushed after every model.
    std::optional<gpu::StageTimestamps> mTimestamps;
    // What the timestamps of the devices finished with measured (finishTimestamps).
    std::vector<gpu::StageTime> mGpuStageTotals;
    std::deque<ChunkInFlight> mChunks;  // In the ring's order.
    ModelLoader* mLoader = nullptr;
    Clock::time_point mLastProgress{};
};

Result<void> BatchRun::createRenderers() {
    render::RendererOptions rendererOptions = mOptions.renderer;
    rendererOptions.target = {mLayout.targetWidth(), mLayout.height, mOptions.samples};
    rendererOptions.culling.levelsOfDetail = mOptions.lodErrorPixels > 0.0f;
    if (rendererOptions.culling.levelsOfDetail) {
        rendererOptions.culling.lodErrorPixels = mOptions.lodErrorPixels;
    }
    rendererOptions.keepPipelines = true;  // Models share most pipelines: create each once.
    // Normal images have a transparent background whatever the colour images have.
    rendererOptions.target.hdr = mOptions.images.normals || mOptions.images.depth;
    // collectRenderer makes sure the GPU is done with a renderer's scene before it prepares.
    rendererOptions.prepareWaitsForIdle = false;
    mRing = nullptr;
    mRenderers.clear();
    // The renderers of an earlier run when they were built from the same options; they light
    // with one environment.
    ENCORE_TRY(mBatchRenderer.acquire(rendererOptions, mOptions.readbackSlots, mOptions.renderers));
    for (std::size_t i = 0; i < mBatchRenderer.rendererCount(); ++i) {
        mRenderers.push_back({&mBatchRenderer.renderer(i), {}});
    }
    mRing = &mBatchRenderer.ring();
    mStaging = std::make_shared<gpu::StagingBuffers>(mContext);
    mTimestamps.reset();
    if (mOptions.gpuTimestamps) {
        mTimestamps = gpu::StageTimestamps::create(mContext, render::kGpuStageCount);
    }
    for (RendererSlot& slot : mRenderers) {
        slot.renderer->setStageTimestamps(mTimestamps ? &*mTimestamps : nullptr);
    }
    return {};
}

void BatchRun::finishTimestamps() {
    for (RendererSlot& slot : mRenderers) {
        slot.renderer->setStageTimestamps(nullptr);  // The renderers may outlive this run.
    }
    if (!mTimestamps) {
        return;
    }
    mTimestamps->finish();
    const std::vector<gpu::StageTime>& measured = mTimestamps->totals();
    mGpuStageTotals.resize(measured.size());
    for (std::size_t stage = 0; stage < measured.size(); ++stage) {
        mGpuStageTotals[stage].milliseconds += measured[stage].milliseconds;
        mGpuStageTotals[stage].timed += measured[stage].timed;
        mGpuStageTotals[stage].untimed += measured[stage].untimed;
    }
    mTimestamps.reset();
}

BatchProgress BatchRun::progress() const {
    BatchProgress progress;
    progress.total = mInputs.size();
    progress.rendered = mCounters.rendered.load();
    progress.failed = mCounters.failed.load();
    progress.skipped = mSkipped;
    progress.views = mCounters.views.load();
    progress.seconds = secondsSince(mStart);
    return progress;
}

void BatchRun::reportProgress(bool force) {
    // Several times a second at most: the callback may print.
    constexpr double kIntervalSeconds = 0.1;
    if (mOptions.progress &&
        (force ||
         std::chrono::duration<double>(Clock::now() - mLastProgress).count() > kIntervalSeconds)) {
        mLastProgress = Clock::now();
        mOptions.progress(progress());
    }
}

void BatchRun::collectOldest() {
    ChunkInFlight chunk = std::move(mChunks.front());
    mChunks.pop_front();
    auto finished = mRing->takeOldestMapped();
    if (!finished) {
        chunk.job->fail(*mFailures, mCounters, "render", finished.error());
        recoverIfLost();
        return;
    }
    mGpuStages.gpu += finished->waitMilliseconds / 1000.0;
    const auto start = Clock::now();
    if (!chunk.job->failed) {
        // The pool crops the strips straight out of the mapped buffer: the device thread copies
        // nothing, and the ring unmaps the buffer once the last strip is cropped.
        auto wide = std::make_shared<const gpu::MappedReadback>(std::move(*finished));
        mWriter->writeViews(chunk.job, chunk.first, chunk.count, chunk.kind, std::move(wide));
    }
    mGpuStages.readback += secondsSince(start);
    reportProgress(false);
}

void BatchRun::collectRenderer(std::size_t slot) {
    // The ring reads back in submission order: once the last read of the renderer's views is
    // taken, the GPU has finished everything the renderer submitted before it.
    const auto drewLast = [&] {
        return std::any_of(mChunks.begin(), mChunks.end(),
                           [&](const ChunkInFlight& chunk) { return chunk.renderer == slot; });
    };
    while (drewLast()) {
        collectOldest();
    }
}

void BatchRun::releasePrepared(RendererSlot& slot) {
    if (slot.prepared) {
        mLoader->release(slot.prepared->bytes);
        slot.prepared.reset();
    }
}

void BatchRun::collectReady() {
    while (!mChunks.empty() && mRing->oldestReady()) {
        collectOldest();
    }
}

void BatchRun::recoverIfLost() {
    if (!mContext.deviceLost()) {
        return;
    }
    // Every read-back in flight belongs to the lost device: those models fail too.
    while (!mChunks.empty()) {
        collectOldest();
    }
    ++mDevicesLost;
    finishTimestamps();
    for (RendererSlot& slot : mRenderers) {
        releasePrepared(slot);
    }
    mRenderers.clear();  // renderModel fails every later model's upload when none is left.
    mRing = nullptr;
    mBatchRenderer.discard();  // Built on the lost device.
    if (auto recreated = mContext.recreateDevice(); recreated) {
        (void)createRenderers();
    }
}

void BatchRun::renderChunk(const TargetViews& views, ViewImage kind, double& waiting) {
    const auto& [job, slot, cameras, first, count] = views;
    if (mRing->full()) {
        const auto waitStart = Clock::now();
        const std::uint64_t device = mDevicesLost;
        collectOldest();
        waiting += secondsSince(waitStart);
        if (device != mDevicesLost) {
            job->fail(*mFailures, mCounters, "render", lostWhileDrawing());
            return;
        }
    }
    render::Renderer& renderer = *mRenderers[slot].renderer;
    renderer.renderViews(cameras);
    auto enqueued =
        mRing->enqueue(renderer.target().colorTexture(), mTimestamps ? &*mTimestamps : nullptr,
                       render::gpuStageIndex(render::GpuStage::ReadbackCopy));
    if (!enqueued) {
        job->fail(*mFailures, mCounters, "render", enqueued.error());
        return;
    }
    mChunks.push_back({job, slot, first, count, kind});
}

void BatchRun::renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                                  render::Renderer& renderer,
                                  render::DebugChannel channel,
                                  const std::function<void()>& draw) {
    const std::uint64_t device = mDevicesLost;
    // After a device loss inside draw() the renderer is gone: nothing to switch back.
    const auto rendererAlive = [&] { return device == mDevicesLost; };
    if (auto drawn = drawDebugChannel(renderer, channel, draw, rendererAlive); !drawn) {
        job->fail(*mFailures, mCounters, "render", drawn.error());
    }
}

void BatchRun::renderDepth(const TargetViews& views, float unitsPerModelUnit, double& waiting) {
    const auto& [job, slot, cameras, first, count] = views;
    render::Renderer& renderer = *mRenderers[slot].renderer;
    renderer.renderViews(cameras);
    // The HDR target holds the depth itself (the channel writes it as colour); read back now,
    // waiting, since depth images are the exception.
    const auto start = Clock::now();
    auto wide = renderer.readHdrImage();
    mGpuStages.gpu += secondsSince(start);
    waiting += secondsSince(start);
    if (!wide) {
        job->fail(*mFailures, mCounters, "render", wide.error());
        return;
    }
    mWriter->writeDepthViews(job, first, count, *wide, mLayout.targetWidth(), unitsPerModelUnit);
}

void BatchRun::renderModel(LoadedModel& loaded) {
    const BatchInput& input = mPending[loaded.order];
    auto job = std::make_shared<ModelJob>();
    job->input = &input;
    job->folder = modelFolder(mOptions.output, input.name);
    job->facts = std::move(loaded.facts);
    job->times.load = loaded.seconds;
    mPlanner->plan(*job);
    // Fails the model before any renderer holds it: its bytes go back to the loader.
    const auto failBeforeUpload = [&](const char* stage, const Error& error) {
        job->fail(*mFailures, mCounters, stage, error);
        mLoader->release(loaded.bytes);
    };
    if (!loaded.scene) {
        failBeforeUpload("load", loaded.scene.error());
        return;
    }
    if (mRenderers.empty()) {
        failBeforeUpload("upload", deviceNotRecreated());
        return;
    }
    if (auto opened = openModelFolder(job->folder); !opened) {
        failBeforeUpload("write", opened.error());
        return;
    }

    // The pool copies the images into staging buffers while this thread waits for the
    // renderer below: prepare then only records copies (StagedImages.h).
    const auto stagingStart = Clock::now();
    const std::unique_ptr<render::StagedImages> staged = render::StagedImages::stage(
        mContext.device(), *loaded.scene, mContext.limits().maxTextureDimension2D,
        [this](std::function<void()> copy) { mPool.submitFirst(std::move(copy)); }, mStaging);
    mGpuStages.staging += secondsSince(stagingStart);
    mGpuStages.upload += secondsSince(stagingStart);

    // The renderer that drew the oldest model in flight prepares this one, while the GPU may
    // still draw the later ones with the others. Its own views must be read back first:
    // preparing frees its scene. (collectOldest counts the wait as the GPU's.)
    const std::size_t slotIndex = mModelsPrepared++ % mRenderers.size();
    collectRenderer(slotIndex);
    collectReady();
    if (mRenderers.empty()) {
        // Collecting found the device lost and could not create it again.
        failBeforeUpload("upload", deviceNotRecreated());
        return;
    }

    if (mOptions.topLightLux > 0.0f) {
        addTopLight(*loaded.scene, mOptions.topLightLux);
    }

    // The renderer refers to the scene it prepared until the next prepare: keep that one alive
    // until now, and this one until the renderer's next model.
    const auto uploadStart = Clock::now();
    RendererSlot& slot = mRenderers[slotIndex];
    render::Renderer& renderer = *slot.renderer;
    const scene::SceneData& scene = *loaded.scene;
    // The model's environment is bound by the prepare() below.
    if (auto lit = mBatchRenderer.light(renderer, job->lighting); !lit) {
        failBeforeUpload("load", lit.error());
        return;
    }
    auto prepared = renderer.prepare(scene, mStrategy.kind, mStrategy.bundle, staged.get());
    releasePrepared(slot);
    slot.prepared = std::move(loaded);
    if (prepared) {
        prepared = mContext.checkNoErrors("Preparing '" + scene.sourcePath.string() + "'");
    }
    mGpuStages.upload += secondsSince(uploadStart);
    job->times.upload = secondsSince(uploadStart);
    mGpuStages.uploadParts += renderer.prepareTimes();
    if (!prepared) {
        job->fail(*mFailures, mCounters, "upload", prepared.error());
        mContext.takeErrors();
        recoverIfLost();
        return;
    }

    const ViewRigOptions& rig = mOptions.views;
    const auto viewCount = std::uint32_t(job->views.size());
    // And one that this thread holds until the model's times are set (ModelWriter::rendered).
    job->remaining = viewCount * mOptions.images.perView() + 1;
    const glm::mat4 toUnitBox = normalization(scene.bounds, rig.normalize);
    const auto renderStart = Clock::now();
    double renderWaiting = 0.0;
    for (std::uint32_t first = 0; first < viewCount; first += mLayout.strips) {
        const std::uint32_t count = std::min<std::uint32_t>(mLayout.strips, viewCount - first);
        const std::vector<render::Camera> cameras =
            stripCameras(job->views, first, mLayout, toUnitBox);
        const TargetViews views{job, slotIndex, cameras, first, count};
        renderChunk(views, ViewImage::Color, renderWaiting);
        if (mOptions.images.normals && !job->failed) {
            renderDebugChannel(job, renderer, render::DebugChannel::Normal,
                               [&] { renderChunk(views, ViewImage::Normal, renderWaiting); });
        }
        if (mOptions.images.depth && !job->failed) {
            renderDebugChannel(job, renderer, render::DebugChannel::Depth,
                               [&] { renderDepth(views, toUnitBox[0][0], renderWaiting); });
        }
        if (job->failed) {
            break;
        }
    }
    if (auto clean = mContext.checkNoErrors("Rendering '" + scene.sourcePath.string() + "'");
        !clean) {
        job->fail(*mFailures, mCounters, "render", clean.error());
        mContext.takeErrors();
        recoverIfLost();
    }
    if (mTimestamps) {
        mTimestamps->flush();  // Every pass of the model is submitted: its mips and views.
    }
    mGpuStages.render += secondsSince(renderStart) - renderWaiting;
    job->times.render = secondsSince(renderStart) - renderWaiting;
    mWriter->rendered(job);
}

Result<BatchSummary> BatchRun::run() {
    const ViewRigOptions& rig = mOptions.views;
    ENCORE_TRY(validateBatchOptions(mOptions));
    ENCORE_TRY_ASSIGN(auto planner, ModelPlanner::create(mOptions));  // Lists the environments.
    mPlanner.emplace(std::move(planner));
    std::error_code ec;
    fs::create_directories(mOptions.output, ec);
    if (ec) {
        return makeError(ErrorCode::IoError, "Cannot create the output folder '" +
                                                 mOptions.output.string() + "' (" + ec.message() +
                                                 ").");
    }
    if (mOptions.writeFailureLog) {
        ENCORE_TRY_ASSIGN(auto failures, FailureLog::create(mOptions.output / "failures.jsonl"));
        mFailures.emplace(std::move(failures));
    } else {
        mFailures.emplace(FailureLog::inMemory());
    }
    mWriter.emplace(mPool, mOptions, *mFailures, mCounters);
    mLayout = stripLayout(mOptions.width, mOptions.height, rig.views, mContext.limits());
    ENCORE_TRY(createRenderers());

    // Finished models are skipped before anything loads.
    for (const BatchInput& input : mInputs) {
        if (modelFinished(modelFolder(mOptions.output, input.name), modelFileSet(mOptions))) {
            ++mSkipped;
        } else {
            mPending.push_back(input);
        }
    }
    mPlanner->groupByEnvironment(mPending);  // Each environment file's maps computed once.
    scene::LoadOptions loadOptions;
    loadOptions.strict = mOptions.strict;
    // Levels of detail only when asked for: they cost load time and memory that only GPUs
    // drawing more than the CPU loads earn back (BatchOptions::lodErrorPixels). The vertex-cache
    // order is kept, but made by the fast FIFO optimiser: the thorough one took a third of the
    // ten shared models' load time (most of it on one sphere grid of a million triangles), more
    // than a few views earn back.
    loadOptions.buildLevelsOfDetail = mOptions.lodErrorPixels > 0.0f;
    loadOptions.vertexCacheOrder = scene::VertexCacheOrder::Fast;
    // One load per pool thread keeps them busy; encode tasks queue between them.
    ModelLoader loader(mPool, mPending, loadOptions, mOptions.memoryLimitBytes, mPool.size());
    mLoader = &loader;
    reportProgress(true);
    bool interrupted = false;
    while (true) {
        if (stopRequested()) {
            interrupted = true;
            break;
        }
        if (!loader.nextReady()) {
            // Keep the GPU thread useful while the next model loads: hand finished views on.
            if (!mChunks.empty()) {
                collectOldest();
                continue;
            }
            if (loader.exhausted()) {
                break;
            }
            loader.waitForNext(100);
            reportProgress(false);
            continue;
        }
        std::optional<LoadedModel> loaded = loader.take();
        {
            std::lock_guard lock(mCounters.mutex);
            mCounters.load += loaded->seconds;
            mCounters.loadCpu += loaded->cpuSeconds;
        }
        renderModel(*loaded);
        collectReady();
        reportProgress(false);
    }
    loader.stop();
    while (!mChunks.empty()) {
        collectOldest();
    }
    loader.finish();
    mPool.waitIdle();
    finishTimestamps();
    // The renderers may serve later runs (BatchRenderer): they must not refer to the scenes
    // freed here, nor hold those scenes' GPU memory.
    for (RendererSlot& slot : mRenderers) {
        slot.renderer->releaseScene();
        slot.prepared.reset();
    }
    mRenderers.clear();

    BatchSummary summary;
    static_cast<BatchProgress&>(summary) = progress();
    summary.interrupted = interrupted || stopRequested();
    summary.stages = mGpuStages;
    summary.stages.gpuStages = mGpuStageTotals;
    summary.stages.load = mCounters.load;
    summary.stages.encode = mCounters.encode;
    summary.stages.loadCpu = mCounters.loadCpu;
    summary.stages.encodeCpu = mCounters.encodeCpu;
    summary.failures = mFailures->entries();
    reportProgress(true);
    return summary;
}

}  // namespace

Result<BatchSummary> runBatch(gpu::Context& context,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options) {
    BatchRenderer renderers(context);
    return runBatch(renderers, inputs, options);
}

Result<BatchSummary> runBatch(BatchRenderer& renderers,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options) {
    BatchRun run(renderers, inputs, options);
    return run.run();
}

}  // namespace encore::batch
