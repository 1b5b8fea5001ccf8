#pragma once

// One device's part of a batch (Batch.h): the thread that takes loaded models, uploads them to
// its renderers, draws their views and reads them back, handing the images to the writer. A
// batch on several devices runs one lane per device, each on its own thread; they share the
// loader, the pool, the writer, the failure log and the counters (BatchShared).

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "batch/BatchRenderer.h"
#include "batch/BatchStrategy.h"
#include "batch/FailureLog.h"
#include "batch/ModelLoader.h"
#include "batch/ModelPlan.h"
#include "batch/ModelSamples.h"
#include "batch/ModelWriter.h"
#include "batch/PngRowsPass.h"
#include "batch/ShardWriter.h"
#include "batch/ViewStrips.h"
#include "core/ThreadPool.h"
#include "encore/batch/Batch.h"
#include "gpu/CreationCounts.h"
#include "gpu/StageTimestamps.h"
#include "gpu/StagingBuffers.h"
#include "gpu/TextureReadbackRing.h"
#include "render/StagedGeometry.h"
#include "render/StagedImages.h"

namespace encore::batch {

// What every lane of a batch uses; owned by the batch's run, which outlives its lanes.
struct BatchShared {
    const BatchOptions& options;
    BatchStrategy strategy;               // BatchOptions::strategy, or auto's per model.
    std::span<const BatchInput> pending;  // Not finished by an earlier run, in load order.
    ThreadPool& pool;
    // Copies models' images and geometry into staging buffers for the device threads, beside
    // the pool (whose threads may all be loading or encoding).
    ThreadPool& stagingCopies;
    FailureLog& failures;
    SharedCounters& counters;
    ModelWriter& writer;
    ModelLoader& loader;
    const ModelPlanner& planner;          // Each model's views and lighting.
    const ShardWriter* shards = nullptr;  // BatchOptions::shards: samples finished in shards.

    bool stopRequested() const { return options.stop && options.stop->load(); }
};

// Views [first, first + count) of a model, drawn side by side in one read-back (ViewStrips.h).
struct ChunkInFlight {
    std::shared_ptr<ModelJob> job;
    std::size_t renderer = 0;  // Which of the lane's renderers drew them.
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    ViewImage kind = ViewImage::Color;
    // A read of half floats (pass targets): the images made from it, and the scale of depths.
    std::vector<ViewImage> floatKinds;
    float unitsPerModelUnit = 1.0f;
    // A read of PNG rows filtered on the GPU (PngRowsPass): where its images lie.
    std::optional<PngRowsLayout> pngRows;
};

// One of the renderers that take models in turn, and the scene it last prepared: the renderer
// refers to that scene (and the loader's bytes behind it) until it prepares the next one.
struct RendererSlot {
    render::Renderer* renderer = nullptr;  // Owned by the lane's BatchRenderer.
    // On the heap: the renderer holds the scene's address, which a move would leave behind.
    std::unique_ptr<LoadedModel> prepared;
    std::shared_ptr<ModelProgress> model;  // Of `prepared`: whether to retry it after a loss.
};

// The views of a model that one target holds: [first, first + count), drawn with `cameras`.
struct TargetViews {
    std::shared_ptr<ModelJob> job;
    std::size_t renderer = 0;  // An index into DeviceLane::mRenderers.
    std::span<const render::Camera> cameras;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

class DeviceLane {
  public:
    DeviceLane(BatchRenderer& renderers, BatchShared& shared)
        : mContext(renderers.context()), mBatchRenderer(renderers), mShared(shared) {}

    // Creates the renderers (and the read-back ring) on the lane's device, one environment for
    // them all, with the stage timestamps when asked for.
    Result<void> createRenderers();
    // Takes models from the loader until it is exhausted or the batch is stopped, then waits for
    // the read-backs still in flight. `idle` is called between models and while waiting for
    // the loader (the batch reports its progress there).
    void run(const std::function<void()>& idle);
    // After run(): ends the timestamps and frees the renderers' scenes (the renderers may serve
    // later batches, BatchRenderer.h).
    void finish();

    // The device thread's stages, the GPU's own times (StageTimes::gpuStages) among them.
    StageTimes stages() const;
    DeviceSummary summary() const;

  private:
    void finishTimestamps();
    // Waits until the GPU is done with what renderer `slot` drew last, handing those views to
    // the encoders, so that it may prepare its next scene without waiting for the others.
    void collectRenderer(std::size_t slot);
    // Frees renderer `slot`'s scene and gives its bytes back to the loader.
    void releasePrepared(RendererSlot& slot);
    // A model's images and geometry on their way into staging buffers (render/StagedImages.h,
    // render/StagedGeometry.h), for the device mDevicesLost counted when they were staged.
    struct StagedModel {
        std::unique_ptr<render::StagedImages> images;
        std::unique_ptr<render::StagedGeometry> geometry;
        std::uint64_t devicesLost = 0;
    };
    // The model taken from the loader while the one before it uploads, its staging started.
    struct ModelAhead {
        LoadedModel loaded;
        StagedModel staged;
    };
    // Hands `scene`'s copies into staging buffers to the staging threads.
    StagedModel stageModel(const scene::SceneData& scene);
    // Takes the next model from the loader, when one has loaded and none is ahead yet, and
    // starts its staging (mAhead): its copies then run while the current model uploads.
    void stageAhead();
    // Gives the model ahead back to the loader unrendered (the batch stops).
    void releaseAhead();
    // Adds a taken model's load times to the counters.
    void countLoad(const LoadedModel& loaded);
    // Uploads a model once and draws each of its samples (ModelSamples.h) from it; `retry`: a
    // second attempt after a device loss (a second loss fails it); `ahead`: its staging when
    // stageAhead started it.
    void renderModel(LoadedModel& loaded, bool retry = false, StagedModel* ahead = nullptr);
    // renderModel's steps. The samples of the model still to draw, its folders opened; none
    // when it failed (listed) or every sample is finished (skipped).
    std::optional<std::vector<ModelSample>> samplesToRender(const LoadedModel& loaded,
                                                            ModelProgress& model);
    // The renderer slot to prepare the model with, once its last model's views are read back;
    // none when the device is lost for good (the model failed).
    std::optional<std::size_t> freeRenderer(const LoadedModel& loaded,
                                            ModelProgress& model,
                                            StagedModel& staged);
    // Lights and prepares the model on the slot's renderer (which then holds `held`): the
    // strategy it was prepared with, or none when it failed.
    std::optional<render::StrategyChoice> uploadModel(std::size_t slotIndex,
                                                      std::unique_ptr<LoadedModel> held,
                                                      const std::shared_ptr<ModelProgress>& model,
                                                      const StagedModel& staged,
                                                      const ModelFacts& facts);
    // Draws every sample from the one upload: between them only the material bindings change.
    void renderSamples(std::size_t slotIndex,
                       const std::shared_ptr<ModelProgress>& model,
                       const std::vector<ModelSample>& samples,
                       const ModelFacts& facts,
                       const render::StrategyChoice& strategy,
                       const ModelTimes& times);
    // Fails a model before any renderer holds it: its bytes go back to the loader.
    void failBeforeUpload(ModelProgress& model,
                          const LoadedModel& loaded,
                          const char* stage,
                          const Error& error);
    // Fails a sample or a model, unless the device is lost and the model was not retried yet:
    // it is then drawn again once the device is recreated (recoverIfLost keeps its scene).
    void failJob(ModelJob& job, const char* stage, const Error& error);
    void failModel(ModelProgress& model, const char* stage, const Error& error);
    bool retryAfterLoss(ModelProgress& model);
    void injectDeviceLossForTests();
    // Draws one sample's views with renderer `slotIndex` (which has the model prepared and the
    // sample's variant selected) and hands them to the writer.
    void renderSample(const std::shared_ptr<ModelJob>& job,
                      std::size_t slotIndex,
                      const scene::SceneData& scene,
                      double& renderWaiting);
    // Takes the oldest read-back and hands its views to the pool.
    void collectOldest();
    void collectReady();
    // Draws the views through `channel` with tone mapping off, then shades again.
    void renderDebugChannel(const std::shared_ptr<ModelJob>& job,
                            render::Renderer& renderer,
                            render::DebugChannel channel,
                            const std::function<void()>& draw);
    // Draws a target's views (through the channel the caller selected) and reads them back now
    // as floats: depth, segmentation; the HDR image reads the colour frame without drawing.
    void renderFloatPass(const TargetViews& views,
                         ViewImage kind,
                         float unitsPerModelUnit,
                         double& waiting);
    // Draws a target's views and starts reading them back; `waiting` adds the time spent
    // waiting for a free read-back slot.
    void renderChunk(const TargetViews& views, ViewImage kind, double& waiting);
    // Starts reading `texture` back for `views` (the images `chunk` names), after a free slot
    // if need be; false when that failed the job (a device lost meanwhile, a failed enqueue).
    bool enqueueReadback(const TargetViews& views,
                         const wgpu::Texture& texture,
                         ChunkInFlight chunk,
                         double& waiting);
    // The same through the PNG rows pass: `source`'s views as the PNG rows of `requests`' images
    // (mPngRows; `depthFactor` as PngRowsPass::record takes it).
    bool enqueuePngRows(const TargetViews& views,
                        const wgpu::TextureView& source,
                        std::span<const PngRowsRequest> requests,
                        float depthFactor,
                        ChunkInFlight chunk,
                        double& waiting);
    // Waits for a free read-back slot if every one is in flight; false when a device loss
    // meanwhile failed the job.
    bool waitForSlot(const TargetViews& views, double& waiting);
    // After renderChunk drew the colour frame with pass targets: reads back every pass image of
    // its views through the ring (renderer.passTexture), the HDR image from the scene colour.
    void readPassTargets(const TargetViews& views, float unitsPerModelUnit, double& waiting);
    // After a failure: a lost device is replaced, and the renderer with it.
    void recoverIfLost();

    gpu::Context& mContext;
    // Owns the renderers and the read-back ring, which may outlive this lane (BatchRenderer.h).
    BatchRenderer& mBatchRenderer;
    BatchShared& mShared;
    StageTimes mStages;  // The device thread's stages.
    StripLayout mLayout;
    // The passes are drawn in the colour frame's render pass (drawsPassTargets), not one frame
    // per pass.
    bool mPassTargets = false;
    // Filters the PNG rows on the GPU (BatchOptions::pngFiltering); the batch renderer's.
    PngRowsPass* mPngRows = nullptr;
    // Models go to the renderers in turn: while the GPU draws model k with one, the device
    // thread uploads model k + 1 with another (BatchOptions::renderers). No renderer is left
    // after a device loss that could not be recovered.
    std::vector<RendererSlot> mRenderers;
    std::uint64_t mModelsPrepared = 0;  // Models handed to a renderer: picks the next one.
    std::uint64_t mViewsDrawn = 0;
    // When the model being drawn passes BatchOptions::modelTimeoutSeconds (max: never).
    std::chrono::steady_clock::time_point mModelDeadline =
        std::chrono::steady_clock::time_point::max();
    // Device losses so far: a renderer used across a collectOldest() may have been replaced.
    std::uint64_t mDevicesLost = 0;
    gpu::TextureReadbackRing* mRing = nullptr;
    // The staging buffers of the models' images: the batch renderer's, reused from model to
    // model and from batch to batch.
    std::shared_ptr<gpu::StagingBuffers> mStaging;
    // With BatchOptions::gpuTimestamps: on the current device, flushed after every model.
    std::optional<gpu::StageTimestamps> mTimestamps;
    // What the timestamps of the devices finished with measured (finishTimestamps).
    std::vector<GpuStageTime> mGpuStageTotals;
    std::deque<ChunkInFlight> mChunks;  // In the ring's order.
    // Models in flight when the device was lost, to draw again (once) on the new one.
    std::deque<LoadedModel> mRetries;
    std::optional<ModelAhead> mAhead;
    std::shared_ptr<ModelProgress> mCurrentModel;  // Uploaded and being drawn by renderModel.
    // What this thread created in the driver: over run(), and up to the last sample handed to
    // the writer (the next sample's `created` starts there).
    gpu::CreationCounts mCreatedInRun;
    gpu::CreationCounts mCreatedMark;
    std::uint64_t mModelsCreating = 0;  // Samples, strictly: one per model without variants.
    bool mInjectedLoss = false;
};

}  // namespace encore::batch
