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
#include "encore/core/FileIO.h"
#include "encore/core/ThreadPool.h"
#include "encore/gpu/TextureReadbackRing.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Counters the pool's encode tasks and the GPU thread both update.
struct SharedCounters {
    std::atomic<std::size_t> rendered{0};
    std::atomic<std::size_t> failed{0};
    std::atomic<std::uint64_t> views{0};
    std::mutex mutex;  // Guards the sums below.
    double load = 0.0;
    double encode = 0.0;
};

// One model from its upload until its last file is written, shared by its encode tasks.
struct ModelJob {
    const BatchInput* input = nullptr;
    fs::path folder;
    std::vector<glm::mat4> cameraToWorld;
    std::atomic<std::uint32_t> remaining{0};  // Images not yet written.
    std::atomic<bool> failed{false};

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

// The views of a model that one target holds: [first, first + count), drawn with `cameras`.
struct TargetViews {
    std::shared_ptr<ModelJob> job;
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
          mRenderers(renderers),
          mInputs(inputs),
          mOptions(options),
          mPool(options.jobs) {}

    Result<BatchSummary> run();

  private:
    Result<void> createRenderer();
    bool stopRequested() const { return mOptions.stop && mOptions.stop->load(); }
    void renderModel(LoadedModel& loaded);
    // Takes the oldest read-back and hands its views to the pool.
    void collectOldest();
    void collectReady();
    void encodeView(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    image::ImageRgba8 image);
    // Encodes one image of `job` on the pool and writes it; the last one completes the model.
    void writeImage(const std::shared_ptr<ModelJob>& job,
                    std::uint32_t view,
                    ViewImage kind,
                    std::function<Result<std::vector<std::uint8_t>>()> encode);
    // Draws the views through `channel` with tone mapping off, then shades again.
    void renderDebugChannel(const std::shared_ptr<ModelJob>& job,
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
    void writeTransforms(ModelJob& job);
    // After a failure: a lost device is replaced, and the renderer with it.
    void recoverIfLost();
    void reportProgress(bool force);
    BatchProgress progress() const;

    gpu::Context& mContext;
    // Owns the renderer and the read-back ring, which may outlive this run (BatchRenderer.h).
    BatchRenderer& mRenderers;
    std::span<const BatchInput> mInputs;
    std::vector<BatchInput> mPending;  // Not finished by an earlier run, in load order.
    const BatchOptions& mOptions;
    ThreadPool mPool;
    Clock::time_point mStart = Clock::now();
    std::optional<FailureLog> mFailures;
    SharedCounters mCounters;
    StageTimes mGpuStages;  // The GPU thread's stages.
    std::size_t mSkipped = 0;
    StripLayout mLayout;
    // mRenderers' renderer and ring; null after a device loss that could not be recovered.
    render::Renderer* mRenderer = nullptr;
    gpu::TextureReadbackRing* mRing = nullptr;
    std::deque<ChunkInFlight> mChunks;  // In the ring's order.
    // The scene last handed to the renderer, which refers to it until the next prepare.
    std::optional<LoadedModel> mPrepared;
    ModelLoader* mLoader = nullptr;
    Clock::time_point mLastProgress{};
};

Result<void> BatchRun::createRenderer() {
    render::RendererOptions rendererOptions = mOptions.renderer;
    rendererOptions.target = {mLayout.targetWidth(), mLayout.height, mOptions.samples};
    rendererOptions.keepPipelines = true;  // Models share most pipelines: create each once.
    // Normal images have a transparent background whatever the colour images have.
    rendererOptions.target.hdr = mOptions.images.normals || mOptions.images.depth;
    mRing = nullptr;
    mRenderer = nullptr;
    // The renderer of an earlier run when it was built from the same options.
    ENCORE_TRY(mRenderers.acquire(rendererOptions, mOptions.readbackSlots));
    mRenderer = &mRenderers.renderer();
    mRing = &mRenderers.ring();
    return {};
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
                          image::ImageRgba8 image) {
    writeImage(job, view, kind, [kind, image = std::move(image)]() mutable {
        if (kind == ViewImage::Normal) {
            decodeNormalImage(image);
        }
        return image::encodePng(image);
    });
}

void BatchRun::writeImage(const std::shared_ptr<ModelJob>& job,
                          std::uint32_t view,
                          ViewImage kind,
                          std::function<Result<std::vector<std::uint8_t>>()> encode) {
    mPool.submit([this, job, view, kind, encode = std::move(encode)] {
        const auto start = Clock::now();
        if (!job->failed) {
            auto png = encode();
            Result<void> written =
                png ? writeFileAtomically(viewImagePath(job->folder, view, kind), *png)
                    : Result<void>(png.error());
            if (!written) {
                job->fail(*mFailures, mCounters, "write", written.error());
            } else if (kind == ViewImage::Color) {
                ++mCounters.views;
            }
        }
        // The last image written completes the model: transforms.json goes last, so its
        // presence says every image is in place.
        if (job->remaining.fetch_sub(1) == 1 && !job->failed) {
            writeTransforms(*job);
        }
        std::lock_guard lock(mCounters.mutex);
        mCounters.encode += secondsSince(start);
    });
}

void BatchRun::collectOldest() {
    ChunkInFlight chunk = std::move(mChunks.front());
    mChunks.pop_front();
    auto finished = mRing->takeOldest();
    if (!finished) {
        chunk.job->fail(*mFailures, mCounters, "render", finished.error());
        recoverIfLost();
        return;
    }
    mGpuStages.gpu += finished->waitMilliseconds / 1000.0;
    const auto start = Clock::now();
    if (!chunk.job->failed) {
        for (std::uint32_t strip = 0; strip < chunk.count; ++strip) {
            encodeView(chunk.job, chunk.first + strip, chunk.kind,
                       cropStrip(finished->image, strip, mOptions.width));
        }
    }
    mGpuStages.readback += finished->copyMilliseconds / 1000.0 + secondsSince(start);
    reportProgress(false);
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
    mRenderer = nullptr;
    mRing = nullptr;
    mRenderers.discard();  // Built on the lost device.
    mPrepared.reset();
    if (auto recreated = mContext.recreateDevice(); recreated) {
        (void)createRenderer();  // On failure mRenderer stays null: later models fail.
    }
}

void BatchRun::renderChunk(const TargetViews& views, ViewImage kind, double& waiting) {
    const auto& [job, cameras, first, count] = views;
    if (mRing->full()) {
        const auto waitStart = Clock::now();
        collectOldest();
        waiting += secondsSince(waitStart);
    }
    mRenderer->renderViews(cameras);
    auto enqueued = mRing->enqueue(mRenderer->target().colorTexture());
    if (!enqueued) {
        job->fail(*mFailures, mCounters, "render", enqueued.error());
        return;
    }
    mChunks.push_back({job, first, count, kind});
}

void BatchRun::renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                                  render::DebugChannel channel,
                                  const std::function<void()>& draw) {
    if (auto drawn = drawDebugChannel(*mRenderer, channel, draw); !drawn) {
        job->fail(*mFailures, mCounters, "render", drawn.error());
    }
}

void BatchRun::renderDepth(const TargetViews& views, float unitsPerModelUnit, double& waiting) {
    const auto& [job, cameras, first, count] = views;
    mRenderer->renderViews(cameras);
    // The HDR target holds the depth itself (the channel writes it as colour); read back now,
    // waiting, since depth images are the exception.
    const auto start = Clock::now();
    auto wide = mRenderer->readHdrImage();
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
                   [depth = std::move(depth)] { return image::encodePng16(depth); });
    }
}

void BatchRun::renderModel(LoadedModel& loaded) {
    const BatchInput& input = mPending[loaded.order];
    auto job = std::make_shared<ModelJob>();
    job->input = &input;
    job->folder = modelFolder(mOptions.output, input.name);
    if (!loaded.scene) {
        job->fail(*mFailures, mCounters, "load", loaded.scene.error());
        mLoader->release(loaded.bytes);
        return;
    }
    if (!mRenderer) {
        job->fail(*mFailures, mCounters, "upload",
                  makeError(ErrorCode::DeviceError,
                            "The GPU device was lost and could not be created again."));
        mLoader->release(loaded.bytes);
        return;
    }
    std::error_code ec;
    fs::create_directories(job->folder, ec);
    if (ec) {
        job->fail(
            *mFailures, mCounters, "write",
            makeError(ErrorCode::IoError, "Cannot create the folder '" + job->folder.string() +
                                              "' (" + ec.message() + ")."));
        mLoader->release(loaded.bytes);
        return;
    }
    removePartialFiles(job->folder);

    // prepare() waits for the GPU to finish the previous model before it frees that model's
    // resources. Waiting here instead counts that time as the GPU's, not the upload's, and hands
    // the finished views to the encoders before the upload keeps this thread busy.
    const auto idleStart = Clock::now();
    mContext.waitForIdle();
    mGpuStages.gpu += secondsSince(idleStart);
    collectReady();

    if (mOptions.topLightLux > 0.0f) {
        addTopLight(*loaded.scene, mOptions.topLightLux);
    }

    // The renderer refers to the scene it prepared until the next prepare: keep that one alive
    // until now, and this one until the next model.
    const auto uploadStart = Clock::now();
    const scene::SceneData& scene = *loaded.scene;
    auto prepared = mRenderer->prepare(scene, mOptions.strategy.kind, mOptions.strategy.bundle);
    if (mPrepared) {
        mLoader->release(mPrepared->bytes);
    }
    mPrepared = std::move(loaded);
    if (prepared) {
        prepared = mContext.checkNoErrors("Preparing '" + scene.sourcePath.string() + "'");
    }
    mGpuStages.upload += secondsSince(uploadStart);
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
        const TargetViews views{job, cameras, first, count};
        renderChunk(views, ViewImage::Color, renderWaiting);
        if (mOptions.images.normals && !job->failed) {
            renderDebugChannel(job, render::DebugChannel::Normal,
                               [&] { renderChunk(views, ViewImage::Normal, renderWaiting); });
        }
        if (mOptions.images.depth && !job->failed) {
            renderDebugChannel(job, render::DebugChannel::Depth,
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
    ENCORE_TRY(createRenderer());

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
    // The renderer may serve later runs (BatchRenderer): it must not refer to the scene freed
    // here, nor hold that scene's GPU memory.
    if (mRenderer) {
        mRenderer->releaseScene();
    }
    mPrepared.reset();

    BatchSummary summary;
    static_cast<BatchProgress&>(summary) = progress();
    summary.interrupted = interrupted || stopRequested();
    summary.stages = mGpuStages;
    summary.stages.load = mCounters.load;
    summary.stages.encode = mCounters.encode;
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
