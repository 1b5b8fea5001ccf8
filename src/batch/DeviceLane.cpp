#include "batch/DeviceLane.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "batch/ModelOutput.h"
#include "batch/ModelSamples.h"
#include "batch/ModelSeed.h"
#include "batch/PassImages.h"
#include "batch/PointCloud.h"
#include "core/Elapsed.h"
#include "gpu/Readback.h"
#include "render/StagedGeometry.h"
#include "render/StagedImages.h"
#include "render/renderer/RendererCore.h"

namespace encore::batch {
namespace {

using Clock = std::chrono::steady_clock;

Error deviceNotRecreated() {
    return makeError(ErrorCode::DeviceError,
                     "The GPU device was lost and could not be created again.");
}

Error timedOut(const BatchInput& input, double limitSeconds, const char* what) {
    char limit[32];
    std::snprintf(limit, sizeof(limit), "%g", limitSeconds);
    return makeError(ErrorCode::LimitExceeded, input.path.string() + ": " + what +
                                                   " took longer than the model time limit (" +
                                                   limit +
                                                   " s with its load); the model was "
                                                   "abandoned.");
}

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

}  // namespace

Result<void> DeviceLane::createRenderers() {
    const BatchOptions& options = mShared.options;
    mLayout =
        stripLayout(options.width, options.height, viewCount(options.views), mContext.limits());
    render::RendererOptions rendererOptions = options.renderer;
    rendererOptions.target = {mLayout.targetWidth(), mLayout.height, options.samples};
    rendererOptions.culling.levelsOfDetail = options.lodErrorPixels > 0.0f;
    if (rendererOptions.culling.levelsOfDetail) {
        rendererOptions.culling.lodErrorPixels = options.lodErrorPixels;
    }
    rendererOptions.keepPipelines = true;  // Models share most pipelines: create each once.
    // Pass images have a transparent background whatever the colour images have; depth,
    // segmentation and HDR images are read from the HDR target.
    rendererOptions.target.hdr = options.images.perView() > 1;
    // Ids from one sample of each pixel, the colour antialiased (render/SampleIdPass.h).
    rendererOptions.target.exactIds = options.images.segmentation && options.samples > 1;
    mPassTargets = drawsPassTargets(options.images, mShared.strategy.base.kind, mContext.limits());
    const bool pngRows =
        filtersPngRowsOnGpu(options.pngFiltering, mContext.adapterDescription().adapterType);
    rendererOptions.target.bytesViews = pngRows;
    rendererOptions.passTargets =
        mPassTargets ? passTargetsFor(options.images.segmentationBy) : render::PassTargets::None;
    // With pass targets every image of a target is one read: as many more slots.
    const std::size_t readsPerTarget =
        mPassTargets ? options.images.perView() -
                           std::size_t(options.images.depth && options.images.segmentation)
                     : 1;
    // collectRenderer makes sure the GPU is done with a renderer's scene before it prepares.
    rendererOptions.prepareWaitsForIdle = false;
    mRing = nullptr;
    mRenderers.clear();
    mPngRows = nullptr;
    // A read of PNG rows stays mapped until the pool has compressed its images, not only
    // cropped them: twice the slots keep the device thread from waiting for them.
    const std::size_t slotsPerRead = pngRows ? 2 : 1;
    // The renderers of an earlier run when they were built from the same options; they light
    // with one environment.
    ENCORE_TRY(mBatchRenderer.acquire(
        rendererOptions, options.readbackSlots * readsPerTarget * slotsPerRead, options.renderers));
    for (std::size_t i = 0; i < mBatchRenderer.rendererCount(); ++i) {
        mRenderers.push_back({&mBatchRenderer.renderer(i), {}});
        // While the loaders read the first models: the first prepare would wait for them.
        ENCORE_TRY(mBatchRenderer.renderer(i).createKeptObjects(mShared.strategy.base.kind));
        if (mShared.strategy.mayChooseVisibility()) {
            ENCORE_TRY(
                mBatchRenderer.renderer(i).createKeptObjects(render::StrategyKind::Visibility));
        }
    }
    mRing = &mBatchRenderer.ring();
    // Every slot sized for a target's read now: a slot first used late (more reads in flight
    // than before) then creates nothing.
    const std::uint32_t bytesPerTexel = rendererOptions.target.hdr ? 8 : 4;
    mRing->reserve(std::uint64_t(gpu::paddedRowBytes(mLayout.targetWidth() * bytesPerTexel)) *
                   mLayout.height);
    mStaging = mBatchRenderer.staging();
    if (pngRows) {
        ENCORE_TRY_ASSIGN(mPngRows, mBatchRenderer.pngRowsPass());
    }
    mTimestamps.reset();
    if (options.gpuTimestamps) {
        mTimestamps = gpu::StageTimestamps::create(mContext, render::kGpuStageCount);
    }
    for (RendererSlot& slot : mRenderers) {
        internals(*slot.renderer).setStageTimestamps(mTimestamps ? &*mTimestamps : nullptr);
    }
    return {};
}

void DeviceLane::finishTimestamps() {
    for (RendererSlot& slot : mRenderers) {
        internals(*slot.renderer)
            .setStageTimestamps(nullptr);  // The renderers may outlive this run.
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

void DeviceLane::releasePrepared(RendererSlot& slot) {
    if (slot.prepared) {
        mShared.loader.release(slot.prepared->bytes);
        slot.prepared.reset();
    }
}

void DeviceLane::renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                                    render::Renderer& renderer,
                                    render::DebugChannel channel,
                                    const std::function<void()>& draw) {
    const std::uint64_t device = mDevicesLost;
    // After a device loss inside draw() the renderer is gone: nothing to switch back.
    const auto rendererAlive = [&] { return device == mDevicesLost; };
    if (auto drawn = drawDebugChannel(renderer, channel, draw, rendererAlive); !drawn) {
        failJob(*job, "render", drawn.error());
    }
}

DeviceLane::StagedModel DeviceLane::stageModel(const scene::SceneData& scene) {
    const auto stagingStart = Clock::now();
    const auto run = [this](std::function<void()> copy) {
        mShared.stagingCopies.submit(std::move(copy));
    };
    StagedModel staged;
    staged.devicesLost = mDevicesLost;
    staged.images = render::StagedImages::stage(
        mContext.device(), scene, mContext.limits().maxTextureDimension2D, run, mStaging);
    staged.geometry =
        render::StagedGeometry::stage(scene, mContext.limits().maxBufferSize, run, mStaging);
    mStages.staging += secondsSince(stagingStart);
    mStages.upload += secondsSince(stagingStart);
    return staged;
}

void DeviceLane::countLoad(const LoadedModel& loaded) {
    std::lock_guard lock(mShared.counters.mutex);
    mShared.counters.load += loaded.seconds;
    mShared.counters.loadCpu += loaded.cpuSeconds;
}

void DeviceLane::stageAhead() {
    if (mAhead || mRenderers.empty() || mShared.stopRequested()) {
        return;
    }
    std::optional<LoadedModel> next = mShared.loader.tryTake();
    if (!next) {
        return;
    }
    countLoad(*next);
    StagedModel staged;
    if (next->scene) {
        staged = stageModel(*next->scene);
    }
    mAhead = ModelAhead{std::move(*next), std::move(staged)};
}

void DeviceLane::releaseAhead() {
    if (mAhead) {
        mShared.loader.release(mAhead->loaded.bytes);  // Not rendered: a later run resumes it.
        mAhead.reset();
    }
}

std::optional<std::vector<ModelSample>> DeviceLane::samplesToRender(const LoadedModel& loaded,
                                                                    ModelProgress& model) {
    const BatchOptions& options = mShared.options;
    if (!loaded.scene) {
        failBeforeUpload(model, loaded, loaded.timedOut ? "timeout" : "load", loaded.scene.error());
        return std::nullopt;
    }
    // The model's time limit counts its load and the work here, not its wait in between.
    mModelDeadline = Clock::time_point::max();
    if (options.modelTimeoutSeconds > 0.0) {
        mModelDeadline = Clock::now() +
                         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                             options.modelTimeoutSeconds - loaded.seconds));
    }
    if (mRenderers.empty()) {
        failBeforeUpload(model, loaded, "upload", deviceNotRecreated());
        return std::nullopt;
    }
    auto samples = modelSamples(options, *model.input, loaded.scene->variants);
    if (!samples) {
        failBeforeUpload(model, loaded, "load", samples.error());  // No such material variant.
        return std::nullopt;
    }
    // With every variant, a model resumes sample by sample.
    std::erase_if(*samples, [&](const ModelSample& sample) {
        return (mShared.shards && mShared.shards->finished(sample.name)) ||
               modelFinished(modelFolder(options.output, sample.name), modelFileSet(options));
    });
    if (samples->empty()) {
        ++mShared.counters.skipped;
        mShared.loader.release(loaded.bytes);
        return std::nullopt;
    }
    for (const ModelSample& sample : *samples) {
        if (auto opened = openModelFolder(modelFolder(options.output, sample.name)); !opened) {
            failBeforeUpload(model, loaded, "write", opened.error());
            return std::nullopt;
        }
    }
    return std::move(*samples);
}

std::optional<std::size_t> DeviceLane::freeRenderer(const LoadedModel& loaded,
                                                    ModelProgress& model,
                                                    StagedModel& staged) {
    // The renderer that drew the oldest model in flight prepares this one, while the GPU may
    // still draw the later ones with the others. Its own views must be read back first:
    // preparing frees its scene. (collectOldest counts the wait as the GPU's.)
    const std::size_t slotIndex = mModelsPrepared++ % mRenderers.size();
    const auto collectStart = Clock::now();
    collectRenderer(slotIndex);
    collectReady();
    if (mModelDeadline != Clock::time_point::max()) {
        mModelDeadline += Clock::now() - collectStart;  // Other models' views: not its time.
    }
    if (mRenderers.empty()) {
        // Collecting found the device lost and could not create it again.
        failBeforeUpload(model, loaded, "upload", deviceNotRecreated());
        return std::nullopt;
    }
    if (staged.devicesLost != mDevicesLost) {
        staged = stageModel(*loaded.scene);  // Collecting found the device lost: stage anew.
    }
    return slotIndex;
}

std::optional<render::StrategyChoice> DeviceLane::uploadModel(
    std::size_t slotIndex,
    std::unique_ptr<LoadedModel> held,
    const std::shared_ptr<ModelProgress>& model,
    const StagedModel& staged,
    const ModelFacts& facts) {
    // The renderer refers to the scene it prepared until the next prepare: keep that one alive
    // until now, and this one (where it lies now) until the renderer's next model.
    const auto uploadStart = Clock::now();
    RendererSlot& slot = mRenderers[slotIndex];
    render::Renderer& renderer = *slot.renderer;
    // Every sample is planned alike (views and lighting come from the seed and the model's
    // name); the model's environment is bound by the prepare() below.
    ModelJob plan;
    plan.model = model;
    mShared.planner.plan(plan);
    if (auto lit = mBatchRenderer.light(renderer, plan.lighting); !lit) {
        failBeforeUpload(*model, *held, "load", lit.error());
        return std::nullopt;
    }
    const scene::SceneData& scene = *held->scene;
    const render::StrategyChoice strategy =
        mShared.strategy.forModel(facts.triangles, scene.drawsOnlyOpaqueStaticTriangles());
    auto prepared = internals(renderer).prepare(scene, strategy.kind, strategy.bundle,
                                                {staged.images.get(), staged.geometry.get()});
    releasePrepared(slot);
    slot.prepared = std::move(held);
    slot.model = model;
    mCurrentModel = model;
    injectDeviceLossForTests();
    if (prepared) {
        prepared = mContext.checkNoErrors("Preparing '" + scene.sourcePath.string() + "'");
    }
    mStages.upload += secondsSince(uploadStart);
    mStages.uploadParts += internals(renderer).prepareTimes();
    if (!prepared) {
        failModel(*model, "upload", prepared.error());
        mContext.takeErrors();
        recoverIfLost();
        return std::nullopt;
    }
    if (Clock::now() > mModelDeadline) {
        failModel(*model, "timeout",
                  timedOut(*model->input, mShared.options.modelTimeoutSeconds, "Uploading"));
        return std::nullopt;
    }
    return strategy;
}

void DeviceLane::renderSamples(std::size_t slotIndex,
                               const std::shared_ptr<ModelProgress>& model,
                               const std::vector<ModelSample>& samples,
                               const ModelFacts& facts,
                               const render::StrategyChoice& strategy,
                               const ModelTimes& times) {
    render::Renderer& renderer = *mRenderers[slotIndex].renderer;
    const scene::SceneData& scene = *mRenderers[slotIndex].prepared->scene;
    model->remaining = std::uint32_t(samples.size());
    const std::uint64_t device = mDevicesLost;
    const auto renderStart = Clock::now();
    double renderWaiting = 0.0;
    for (const ModelSample& sample : samples) {
        auto job = std::make_shared<ModelJob>();
        job->model = model;
        job->variant = sample.variantName;
        job->folder = modelFolder(mShared.options.output, sample.name);
        job->facts = facts;
        job->drawing.strategy = render::strategyChoiceName(strategy);
        job->times.load = times.load;
        job->times.upload = times.upload;
        mShared.planner.plan(*job);
        if (auto selected = renderer.selectVariant(sample.variant); !selected) {
            failJob(*job, "render", selected.error());
            break;
        }
        renderSample(job, slotIndex, scene, renderWaiting);
        // A lost device took the renderer with it.
        if (job->failed || device != mDevicesLost) {
            break;
        }
    }
    if (mTimestamps) {
        mTimestamps->flush();  // Every pass of the model is submitted: its mips and views.
    }
    mStages.render += secondsSince(renderStart) - renderWaiting;
}

void DeviceLane::renderModel(LoadedModel& loaded, bool retry, StagedModel* ahead) {
    auto model = std::make_shared<ModelProgress>();
    model->input = &mShared.pending[loaded.order];
    model->retried = retry;
    const std::optional<std::vector<ModelSample>> samples = samplesToRender(loaded, *model);
    if (!samples) {
        return;
    }
    // The staging threads copy the images and the geometry into staging buffers while this thread
    // waits for the renderer below: prepare then only records copies. Staged as the previous
    // model uploaded when it was taken then (stageAhead).
    StagedModel staged =
        ahead && ahead->devicesLost == mDevicesLost ? std::move(*ahead) : stageModel(*loaded.scene);
    // The next model's copies run while this one waits for its renderer and uploads.
    stageAhead();
    const std::optional<std::size_t> slotIndex = freeRenderer(loaded, *model, staged);
    if (!slotIndex) {
        return;
    }
    if (mShared.options.topLightLux > 0.0f && !retry) {  // A retried scene has its light.
        addTopLight(*loaded.scene, mShared.options.topLightLux);
    }
    const ModelFacts facts = loaded.facts;  // Each sample's metadata.json names them.
    ModelTimes times;
    times.load = loaded.seconds;
    const auto uploadStart = Clock::now();
    const std::optional<render::StrategyChoice> strategy = uploadModel(
        *slotIndex, std::make_unique<LoadedModel>(std::move(loaded)), model, staged, facts);
    times.upload = secondsSince(uploadStart);
    if (strategy) {
        // Every sample from this one upload: between them only the material bindings change.
        renderSamples(*slotIndex, model, *samples, facts, *strategy, times);
    }
}

void DeviceLane::renderSample(const std::shared_ptr<ModelJob>& job,
                              std::size_t slotIndex,
                              const scene::SceneData& scene,
                              double& renderWaiting) {
    render::Renderer& renderer = *mRenderers[slotIndex].renderer;
    const auto sampleStart = Clock::now();
    const double waitingBefore = renderWaiting;
    const ViewRigOptions& rig = mShared.options.views;
    const auto viewCount = std::uint32_t(job->views.size());
    // And one that this thread holds until the model's times are set (ModelWriter::rendered).
    const std::uint32_t points = mShared.options.pointCloudPoints;
    job->remaining = viewCount * mShared.options.images.perView() + 1 + std::uint32_t(points > 0);
    const glm::mat4 toUnitBox = normalization(scene.bounds, rig.normalize);
    job->normalization = toUnitBox;
    const ExtraImages& images = mShared.options.images;
    if (points > 0) {
        // Drawn here, where the scene is (cheap beside the views: one pass over the triangles);
        // encoded and written on the pool.
        auto cloud = std::make_shared<const std::vector<SurfacePoint>>(samplePointCloud(
            scene, toUnitBox, points, modelSeed(rig.seed, job->model->input->name)));
        mShared.writer.writeModelFile(
            job, kPointCloudFileName,
            [cloud]() -> Result<std::vector<std::uint8_t>> { return encodePly(*cloud); });
    }
    const std::vector<ViewImage> passes = extraPasses(images);
    if (images.segmentation) {
        job->segmentation = segmentationNames(scene, images.segmentationBy);
    }
    for (std::uint32_t first = 0; first < viewCount; first += mLayout.strips) {
        if (Clock::now() > mModelDeadline) {
            // What is on the GPU already is read back and dropped (the job has failed).
            failJob(*job, "timeout",
                    timedOut(*job->model->input, mShared.options.modelTimeoutSeconds, "Drawing"));
            break;
        }
        const std::uint32_t count = std::min<std::uint32_t>(mLayout.strips, viewCount - first);
        const std::vector<render::Camera> cameras =
            stripCameras(job->views, first, mLayout, toUnitBox);
        const TargetViews views{job, slotIndex, cameras, first, count};
        renderChunk(views, ViewImage::Color, renderWaiting);
        if (mPassTargets) {
            // Every pass was drawn with the colour: read back, nothing more drawn.
            if (!job->failed) {
                readPassTargets(views, toUnitBox[0][0], renderWaiting);
            }
            if (job->failed) {
                break;
            }
            continue;
        }
        // The HDR image is the colour frame's linear colour: read before another pass draws.
        if (images.hdr && !job->failed) {
            renderFloatPass(views, ViewImage::Hdr, toUnitBox[0][0], renderWaiting);
        }
        // Every other pass draws the views once more through its debug channel.
        for (const ViewImage kind : passes) {
            if (job->failed || kind == ViewImage::Hdr) {
                continue;
            }
            const bool floats = kind == ViewImage::Depth || kind == ViewImage::Segmentation ||
                                kind == ViewImage::Coordinates ||
                                (kind == ViewImage::Normal && images.normalsAsFloats());
            const render::DebugChannel channel = passChannel(kind, images);
            renderDebugChannel(job, renderer, channel, [&] {
                if (floats) {
                    renderFloatPass(views, kind, toUnitBox[0][0], renderWaiting);
                } else {
                    renderChunk(views, kind, renderWaiting);
                }
            });
        }
        if (job->failed) {
            break;
        }
    }
    if (auto clean = mContext.checkNoErrors("Rendering '" + scene.sourcePath.string() + "'");
        !clean) {
        failJob(*job, "render", clean.error());
        mContext.takeErrors();
        recoverIfLost();
    }
    job->times.render = secondsSince(sampleStart) - (renderWaiting - waitingBefore);
    const gpu::CreationCounts created = gpu::threadCreationCounts();
    const gpu::CreationCounts sampleCreated = created - mCreatedMark;
    mCreatedMark = created;
    job->drawing.objectsCreated = sampleCreated.objects();
    job->drawing.bytesMapped = sampleCreated.bytesMapped;
    mModelsCreating += sampleCreated.objects() > 0 || sampleCreated.bytesMapped > 0;
    mShared.writer.rendered(job);
}

void DeviceLane::run(const std::function<void()>& idle) {
    ModelLoader& loader = mShared.loader;
    const gpu::CreationCounts runStart = gpu::threadCreationCounts();
    mCreatedMark = runStart;
    while (true) {
        if (mShared.stopRequested()) {
            loader.stop();
            releaseAhead();
            break;
        }
        if (!mRetries.empty()) {
            // The pool may still hold tasks of the lost device's attempt at these models, which
            // would remove the partial files of the new attempt: let them end first.
            mShared.pool.waitIdle();
            LoadedModel retry = std::move(mRetries.front());
            mRetries.pop_front();
            renderModel(retry, /*retry=*/true);
            mCurrentModel.reset();
            collectReady();
            idle();
            continue;
        }
        if (mAhead) {
            ModelAhead ahead = std::move(*mAhead);
            mAhead.reset();
            renderModel(ahead.loaded, /*retry=*/false, &ahead.staged);
            mCurrentModel.reset();
            collectReady();
            idle();
            continue;
        }
        std::optional<LoadedModel> loaded = loader.tryTake();
        if (!loaded) {
            // Keep the device thread useful while the next model loads: hand finished views on.
            if (!mChunks.empty()) {
                collectOldest();
                continue;
            }
            if (loader.exhausted()) {
                break;
            }
            loader.waitForNext(100);
            idle();
            continue;
        }
        countLoad(*loaded);
        renderModel(*loaded);
        mCurrentModel.reset();
        collectReady();
        idle();
    }
    while (!mChunks.empty()) {
        collectOldest();
    }
    mCreatedInRun = gpu::threadCreationCounts() - runStart;
}

void DeviceLane::finish() {
    finishTimestamps();
    // The renderers may serve later runs (BatchRenderer): they must not refer to the scenes
    // freed here, nor hold those scenes' GPU memory.
    for (RendererSlot& slot : mRenderers) {
        slot.renderer->releaseScene();
        slot.prepared.reset();
    }
    mRenderers.clear();
}

StageTimes DeviceLane::stages() const {
    StageTimes stages = mStages;
    stages.gpuStages = mGpuStageTotals;
    return stages;
}

DeviceSummary DeviceLane::summary() const {
    DeviceSummary summary;
    summary.adapter = mContext.adapterDescription().summary();
    summary.device = mContext.adapterDescription().index;
    summary.models = mModelsPrepared;
    summary.views = mViewsDrawn;
    summary.passTargets = mPassTargets;
    summary.pngRowsOnGpu = mPngRows != nullptr;
    summary.gpuObjectsCreated = mCreatedInRun.objects();
    summary.gpuBytesMapped = mCreatedInRun.bytesMapped;
    summary.modelsCreatingGpuObjects = mModelsCreating;
    return summary;
}

}  // namespace encore::batch
