#include "encore/batch/Batch.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "ModelLoader.h"
#include "encore/batch/BatchRenderer.h"
#include "encore/batch/FailureLog.h"
#include "encore/batch/ModelOutput.h"
#include "encore/batch/TransformsJson.h"
#include "encore/batch/ViewStrips.h"
#include "encore/core/Elapsed.h"
#include "encore/core/FileIO.h"
#include "encore/core/ThreadPool.h"
#include "encore/gpu/StageTimestamps.h"
#include "encore/gpu/StagingBuffers.h"
#include "encore/gpu/TextureReadbackRing.h"
#include "encore/render/StagedImages.h"

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

// Counters the pool's encode tasks and the GPU thread both update.
struct SharedCounters {
    std::atomic<std::size_t> rendered{0};
    std::atomic<std::size_t> failed{0};
    std::atomic<std::uint64_t> views{0};
    std::mutex mutex;  // Guards the sums below.
    double load = 0.0;
    double encode = 0.0;
    double loadCpu = 0.0;
    double encodeCpu = 0.0;
};

// One model from its upload until its last file is written, shared by its encode tasks.
struct ModelJob {
    const BatchInput* input = nullptr;
    fs::path folder;
    std::vector<glm::mat4> cameraToWorld;
    std::atomic<std::uint32_t> remaining{0};  // Images not yet written.
    std::atomic<bool> failed{false};
    // Images written under their partial names, flushed and renamed together by the last one.
    std::mutex writtenMutex;
    std::vector<fs::path> written;

    // Records the model's first failure; later ones (other views) add nothing.
    void fail(FailureLog& log,
              SharedCounters& counters,
              const std::string& stage,
              const Error& error) {
        if (!failed.exchange(true)) {
            log.record(input->path, stage, error.message);
            ++counters.failed;
        }
    }
};

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
          mStrategy(options.strategy.value_or(render::StrategyChoice::of(
              options.lodErrorPixels > 0.0f ? render::StrategyKind::GpuCullingBundles
                                            : render::StrategyKind::Bundles,
              false))),
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
    // Crops strip `strip` of a read-back target on the pool, ahead of other tasks (the ring
    // waits for its buffer), then encodes it.
    void encodeView(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::shared_ptr<const gpu::MappedReadback> wide,
                    std::uint32_t strip);
    // Encodes one image of `job` on the pool and writes it; the last one completes the model.
    void writeImage(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::function<Result<std::vector<std::uint8_t>>()> encode);
    // Draws the views through `channel` with tone mapping off, then shades again.
    void renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                            render::Renderer& renderer,
                            render::DebugChannel channel,
                            const std::function<void()>& draw);
    // Draws a target's views through the depth channel and reads them back now.
    void renderDepth(const TargetViews& views, float unitsPerModelUnit, double& waiting);
    // What one step of a 16-bit depth value is, in transforms.json's units: the depth range
    // covers twice the camera distance.
    double depthScale() const { return batch::depthScale(mOptions.views); }
    // Draws a target's views and starts reading them back; `waiting` adds the time spent
    // waiting for a free read-back slot.
    void renderChunk(const TargetViews& views, ViewImage kind, double& waiting);
    // Flushes and renames the model's images (or removes them if it failed), then writes
    // transforms.json.
    void finishImages(ModelJob& job);
    void writeTransforms(ModelJob& job);
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
    StageTimes mGpuStages;  // The device thread's stages.
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

void BatchRun::writeTransforms(ModelJob& job) {
    const nlohmann::json json =
        transformsJson(glm::radians(mOptions.views.horizontalFovDegrees), mOptions.width,
                       mOptions.height, job.cameraToWorld, mOptions.images, depthScale());
    const std::string text = json.dump(2) + "\n";
    auto written = writeFileAtomically(
        job.folder / kTransformsFileName,
        std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    if (!written) {
        job.fail(*mFailures, mCounters, "write", written.error());
        return;
    }
    ++mCounters.rendered;
}

void BatchRun::encodeView(const std::shared_ptr<ModelJob>& job,
                          std::uint32_t view,
                          ViewImage kind,
                          std::shared_ptr<const gpu::MappedReadback> wide,
                          std::uint32_t strip) {
    mPool.submitFirst([this, job, view, kind, wide = std::move(wide), strip]() mutable {
        const auto start = Clock::now();
        const double cpuStart = threadCpuSeconds();
        auto image = std::make_shared<image::ImageRgba8>(
            cropStrip(wide->rows, wide->bytesPerRow, wide->height, strip, mOptions.width));
        wide.reset();  // The last strip lets the ring have its buffer back.
        {
            std::lock_guard lock(mCounters.mutex);
            mCounters.encode += secondsSince(start);
            mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
        }
        writeImage(job, view, kind, [kind, image, compression = mOptions.pngCompression] {
            if (kind == ViewImage::Normal) {
                decodeNormalImage(*image);
            }
            return image::encodePng(*image, compression);
        });
    });
}

void BatchRun::writeImage(const std::shared_ptr<ModelJob>& job,
                          std::uint32_t view,
                          ViewImage kind,
                          std::function<Result<std::vector<std::uint8_t>>()> encode) {
    mPool.submit([this, job, view, kind, encode = std::move(encode)] {
        const auto start = Clock::now();
        const double cpuStart = threadCpuSeconds();
        if (!job->failed) {
            auto png = encode();
            const fs::path path = viewImagePath(job->folder, view, kind);
            Result<void> written = png ? writePartialFile(path, *png) : Result<void>(png.error());
            if (!written) {
                job->fail(*mFailures, mCounters, "write", written.error());
            } else {
                std::lock_guard lock(job->writtenMutex);
                job->written.push_back(path);
            }
            if (written && kind == ViewImage::Color) {
                ++mCounters.views;
            }
        }
        // The last image written completes the model: its images are flushed and renamed
        // together, then transforms.json goes last, so its presence says every image is in
        // place.
        if (job->remaining.fetch_sub(1) == 1) {
            finishImages(*job);
        }
        std::lock_guard lock(mCounters.mutex);
        mCounters.encode += secondsSince(start);
        mCounters.encodeCpu += threadCpuSeconds() - cpuStart;
    });
}

void BatchRun::finishImages(ModelJob& job) {
    if (!job.failed) {
        if (auto committed = commitFiles(job.written); !committed) {
            job.fail(*mFailures, mCounters, "write", committed.error());
        }
    }
    if (job.failed) {
        // A failed model leaves no partial files; its finished images are redone next run.
        for (const fs::path& path : job.written) {
            std::error_code ignored;
            fs::remove(partialPath(path), ignored);
        }
        return;
    }
    writeTransforms(job);
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
        for (std::uint32_t strip = 0; strip < chunk.count; ++strip) {
            encodeView(chunk.job, chunk.first + strip, chunk.kind, wide, strip);
        }
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
    for (std::uint32_t strip = 0; strip < count; ++strip) {
        image::ImageGray16 depth = depthStrip(*wide, mLayout.targetWidth(), strip, mOptions.width,
                                              mOptions.height, unitsPerModelUnit, depthScale());
        writeImage(job, first + strip, ViewImage::Depth,
                   [depth = std::move(depth), compression = mOptions.pngCompression] {
                       return image::encodePng16(depth, compression);
                   });
    }
}

void BatchRun::renderModel(LoadedModel& loaded) {
    const BatchInput& input = mPending[loaded.order];
    auto job = std::make_shared<ModelJob>();
    job->input = &input;
    job->folder = modelFolder(mOptions.output, input.name);
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
    std::error_code ec;
    fs::create_directories(job->folder, ec);
    if (ec) {
        failBeforeUpload("write", makeError(ErrorCode::IoError,
                                            "Cannot create the folder '" + job->folder.string() +
                                                "' (" + ec.message() + ")."));
        return;
    }
    removePartialFiles(job->folder);

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
    auto prepared =
        renderer.prepare(scene, mStrategy.kind, mStrategy.bundle, staged.get());
    releasePrepared(slot);
    slot.prepared = std::move(loaded);
    if (prepared) {
        prepared = mContext.checkNoErrors("Preparing '" + scene.sourcePath.string() + "'");
    }
    mGpuStages.upload += secondsSince(uploadStart);
    mGpuStages.uploadParts += renderer.prepareTimes();
    if (!prepared) {
        job->fail(*mFailures, mCounters, "upload", prepared.error());
        mContext.takeErrors();
        recoverIfLost();
        return;
    }

    const ViewRigOptions& rig = mOptions.views;
    job->cameraToWorld = viewMatrices(rig);
    job->remaining = std::uint32_t(job->cameraToWorld.size()) * mOptions.images.perView();
    const glm::mat4 toUnitBox = normalization(scene.bounds, rig.normalize);
    const float fov = glm::radians(rig.horizontalFovDegrees);
    const auto renderStart = Clock::now();
    double renderWaiting = 0.0;
    for (std::uint32_t first = 0; first < job->cameraToWorld.size(); first += mLayout.strips) {
        const std::uint32_t count = std::min<std::uint32_t>(
            mLayout.strips, std::uint32_t(job->cameraToWorld.size()) - first);
        const std::vector<render::Camera> cameras =
            stripCameras(job->cameraToWorld, first, mLayout, toUnitBox, fov);
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
}

Result<BatchSummary> BatchRun::run() {
    const ViewRigOptions& rig = mOptions.views;
    if (mOptions.width == 0 || mOptions.height == 0 || rig.views == 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch needs at least one view of at least one pixel.");
    }
    if (!(rig.horizontalFovDegrees > 0.0f && rig.horizontalFovDegrees < 180.0f) ||
        !(rig.distance > 0.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The field of view (" + std::to_string(rig.horizontalFovDegrees) +
                             " degrees) must lie in (0, 180) and the distance (" +
                             std::to_string(rig.distance) + ") must be positive.");
    }
    if (!(mOptions.lodErrorPixels >= 0.0f) || (mOptions.lodErrorPixels > 0.0f &&
                                               !render::cullsOnTheGpu(mStrategy.kind))) {
        return makeError(ErrorCode::InvalidArgument,
                         "Levels of detail (an error of " +
                             std::to_string(mOptions.lodErrorPixels) +
                             " pixels) need a non-negative error and a gpu-culling strategy, "
                             "which chooses the levels (not " +
                             render::strategyChoiceName(mStrategy) + ").");
    }
    if (mOptions.renderers < 1 || mOptions.renderers > kMaxRenderers) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch takes 1 to " + std::to_string(kMaxRenderers) +
                             " renderers (asked for " + std::to_string(mOptions.renderers) + ").");
    }
    std::error_code ec;
    fs::create_directories(mOptions.output, ec);
    if (ec) {
        return makeError(ErrorCode::IoError, "Cannot create the output folder '" +
                                                 mOptions.output.string() + "' (" + ec.message() +
                                                 ").");
    }
    if (mOptions.writeFailureLog) {
        auto failures = FailureLog::create(mOptions.output / "failures.jsonl");
        if (!failures) {
            return failures.error();
        }
        mFailures.emplace(std::move(*failures));
    } else {
        mFailures.emplace(FailureLog::inMemory());
    }
    mLayout = stripLayout(mOptions.width, mOptions.height, rig.views, mContext.limits());
    ENCORE_TRY(createRenderers());

    // Finished models are skipped before anything loads.
    for (const BatchInput& input : mInputs) {
        if (modelFinished(modelFolder(mOptions.output, input.name), rig.views, mOptions.images)) {
            ++mSkipped;
        } else {
            mPending.push_back(input);
        }
    }
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
