#include "encore/batch/Batch.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "batch/BatchOptionsValidation.h"
#include "batch/BatchRenderer.h"
#include "batch/BatchStrategy.h"
#include "batch/DeviceLane.h"
#include "batch/FailureLog.h"
#include "batch/ModelLoader.h"
#include "batch/ModelOutput.h"
#include "batch/ModelPlan.h"
#include "batch/ModelSamples.h"
#include "batch/ModelWriter.h"
#include "batch/ShardWriter.h"
#include "core/Elapsed.h"
#include "core/ProcessMemory.h"
#include "core/ThreadPool.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The pool runs at a lower priority than the device threads: with a thread per core loading
// and encoding, a device thread (uploads, recording, read-back, the GPU's only feeder) otherwise
// waits for a core behind them while the GPU runs dry.
constexpr int kPoolNiceness = 10;
// Threads per device that copy the models' images and geometry into staging buffers, at the
// device threads' priority. With the copies on the pool, a device thread whose copy no pool
// thread had reached (every one busy loading or encoding) made it itself: on the 4 x H200
// machine that was 1.4 ms of each model's 7 ms upload (issue 48).
constexpr std::size_t kStagingThreadsPerDevice = 2;

void addStages(StageTimes& sum, const StageTimes& lane) {
    sum.upload += lane.upload;
    sum.staging += lane.staging;
    sum.render += lane.render;
    sum.gpu += lane.gpu;
    sum.readback += lane.readback;
    sum.uploadParts += lane.uploadParts;
    sum.gpuStages.resize(std::max(sum.gpuStages.size(), lane.gpuStages.size()));
    for (std::size_t stage = 0; stage < lane.gpuStages.size(); ++stage) {
        sum.gpuStages[stage].milliseconds += lane.gpuStages[stage].milliseconds;
        sum.gpuStages[stage].timed += lane.gpuStages[stage].timed;
        sum.gpuStages[stage].untimed += lane.gpuStages[stage].untimed;
    }
}

// A batch: what its devices share (the pool, the loader, the writer, the failure log), and the
// device lanes that take the models.
class BatchRun {
  public:
    BatchRun(std::span<BatchRenderer* const> devices,
             std::span<const BatchInput> inputs,
             const BatchOptions& options)
        : mDevices(devices),
          mInputs(inputs),
          mOutput(options.output),
          mOptions(options),
          mPoolOwner(std::make_unique<ThreadPool>(options.jobs, kPoolNiceness)),
          mPool(*mPoolOwner),
          mStagingCopies(std::max<std::size_t>(devices.size(), 1) * kStagingThreadsPerDevice) {}

    Result<BatchSummary> run();

  private:
    // Creates every lane's renderers, the lanes' devices at once (each computes its own
    // environment maps and pipelines).
    Result<void> createLanes(BatchShared& shared);
    // Runs the lanes until the loader is exhausted: the only lane on this thread, several on a
    // thread each while this one reports the progress.
    void runLanes();
    void reportProgress(bool force);
    BatchProgress progress() const;

    std::span<BatchRenderer* const> mDevices;
    std::span<const BatchInput> mInputs;
    std::vector<BatchInput> mPending;  // Not finished by an earlier run, in load order.
    std::filesystem::path mOutput;     // The caller's BatchOptions::output.
    // The caller's options; with shards, `output` is the staging folder the samples are written
    // to before they go into a shard.
    BatchOptions mOptions;
    std::unique_ptr<ShardWriter> mShards;
    // The loading and encoding threads. Left to the process when a load is stuck in the kernel
    // (ModelLoader::finish): destroying it would wait for that load for ever.
    std::unique_ptr<ThreadPool> mPoolOwner;
    ThreadPool& mPool;
    ThreadPool mStagingCopies;  // Shared by the lanes (BatchShared::stagingCopies).
    Clock::time_point mStart = Clock::now();
    std::optional<FailureLog> mFailures;
    SharedCounters mCounters;
    std::vector<std::unique_ptr<DeviceLane>> mLanes;
    std::size_t mSkipped = 0;
    Clock::time_point mLastProgress{};
};

BatchProgress BatchRun::progress() const {
    BatchProgress progress;
    progress.total = mInputs.size();
    progress.rendered = mCounters.rendered.load();
    progress.failed = mCounters.failed.load();
    progress.skipped = mSkipped + mCounters.skipped.load();
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

Result<void> BatchRun::createLanes(BatchShared& shared) {
    for (BatchRenderer* device : mDevices) {
        mLanes.push_back(std::make_unique<DeviceLane>(*device, shared));
    }
    if (mLanes.size() == 1) {
        return mLanes.front()->createRenderers();
    }
    std::vector<Result<void>> created(mLanes.size());
    {
        std::vector<std::jthread> threads;
        for (std::size_t lane = 0; lane < mLanes.size(); ++lane) {
            threads.emplace_back([&, lane] { created[lane] = mLanes[lane]->createRenderers(); });
        }
    }
    for (const Result<void>& result : created) {
        ENCORE_TRY(result);
    }
    return {};
}

void BatchRun::runLanes() {
    if (mLanes.size() == 1) {
        mLanes.front()->run([this] { reportProgress(false); });
        return;
    }
    std::mutex mutex;
    std::condition_variable finished;
    std::size_t running = mLanes.size();
    {
        std::vector<std::jthread> threads;
        for (const std::unique_ptr<DeviceLane>& lane : mLanes) {
            threads.emplace_back([&, lane = lane.get()] {
                lane->run([] {});
                std::lock_guard lock(mutex);
                --running;
                finished.notify_all();
            });
        }
        std::unique_lock lock(mutex);
        while (!finished.wait_for(lock, std::chrono::milliseconds(100),
                                  [&] { return running == 0; })) {
            lock.unlock();
            reportProgress(false);
            lock.lock();
        }
    }
}

Result<BatchSummary> BatchRun::run() {
    ENCORE_TRY(validateBatchOptions(mOptions));
    // Models allocate and free the same large blocks: let later ones reuse the pages.
    keepFreedMemoryInProcess();
    ENCORE_TRY_ASSIGN(auto planner, ModelPlanner::create(mOptions));  // Lists the environments.
    if (mDevices.empty()) {
        return makeError(ErrorCode::InvalidArgument, "A batch needs at least one device.");
    }
    std::error_code ec;
    fs::create_directories(mOptions.output, ec);
    if (ec) {
        return makeError(ErrorCode::IoError, "Cannot create the output folder '" +
                                                 mOptions.output.string() + "' (" + ec.message() +
                                                 ").");
    }
    if (mOptions.shards > 0 || mOptions.shardBytes > 0) {
        const std::uint64_t samplesPerShard =
            mOptions.shards > 0 ? (mInputs.size() + mOptions.shards - 1) / mOptions.shards : 0;
        ENCORE_TRY_ASSIGN(mShards,
                          ShardWriter::open(mOutput, samplesPerShard, mOptions.shardBytes));
        ENCORE_TRY(mShards->addStaged());  // What a killed run left finished.
        mOptions.output = mShards->stagingFolder();
    }
    if (mOptions.writeFailureLog) {
        ENCORE_TRY_ASSIGN(auto failures, FailureLog::create(mOutput / "failures.jsonl"));
        mFailures.emplace(std::move(failures));
    } else {
        mFailures.emplace(FailureLog::inMemory());
    }
    ModelWriter writer(mPool, mOptions, *mFailures, mCounters, mShards.get());

    // Finished models are skipped before anything loads (with variants, a model's samples in
    // shards are only known once loaded: DeviceLane skips those).
    const bool oneSample = mOptions.variant.empty() && !mOptions.allVariants;
    for (const BatchInput& input : mInputs) {
        if ((mShards && oneSample && mShards->finished(input.name)) ||
            samplesFinished(mOptions, input)) {
            ++mSkipped;
        } else {
            mPending.push_back(input);
        }
    }
    planner.groupByEnvironment(mPending);  // Each environment file's maps computed once.
    scene::LoadOptions loadOptions;
    loadOptions.strict = mOptions.strict;
    loadOptions.allowUrisOutside = mOptions.allowUrisOutside;
    // A model larger than everything the batch may hold loaded fails instead of taking the
    // machine's memory.
    loadOptions.maxModelBytes = mOptions.memoryLimitBytes;
    // Levels of detail only when asked for: they cost load time and memory that only GPUs
    // drawing more than the CPU loads earn back (BatchOptions::lodErrorPixels). The vertex-cache
    // order is kept, but made by the fast FIFO optimiser: the thorough one took a third of the
    // ten shared models' load time (most of it on one sphere grid of a million triangles), more
    // than a few views earn back.
    loadOptions.buildLevelsOfDetail = mOptions.lodErrorPixels > 0.0f;
    loadOptions.vertexCacheOrder = scene::VertexCacheOrder::Fast;
    std::vector<gpu::Context*> contexts;
    for (BatchRenderer* device : mDevices) {
        contexts.push_back(&device->context());
    }
    const BatchStrategy strategy = batchStrategyFor(mOptions, contexts);
    // Clusters only for the models the strategy that culls them draws: they doubled a dense
    // model's load.
    loadOptions.buildClusters = strategy.buildsClusters();
    loadOptions.clustersFromTriangles = strategy.clustersFromTriangles();
    loadOptions.clustersForOpaqueStatic = strategy.visibilityForOpaqueStatic;
    loadOptions.maxImageDimension = mOptions.maxTextureSize;
    // One load per pool thread keeps them busy; encode tasks queue between them. With several
    // devices, each takes whichever model has loaded: a slow load holds up none of the others.
    ModelLoader loader(
        mPool, mPending, loadOptions, mOptions.memoryLimitBytes, mPool.size(),
        mDevices.size() == 1 ? ModelLoader::Order::InOrder : ModelLoader::Order::AsLoaded,
        mOptions.modelTimeoutSeconds);
    BatchShared shared{mOptions,  strategy, mPending, mPool,   mStagingCopies, *mFailures,
                       mCounters, writer,   loader,   planner, mShards.get()};
    if (auto created = createLanes(shared); !created) {
        loader.finish();
        return created.error();
    }

    reportProgress(true);
    runLanes();
    const std::size_t stuckLoads = loader.finish();
    mPool.waitIdle(stuckLoads);
    if (stuckLoads > 0) {
        ThreadPool::abandon(std::move(mPoolOwner));
    }
    if (mShards) {
        ENCORE_TRY(mShards->close());  // The last shard, with fewer samples.
    }

    BatchSummary summary;
    static_cast<BatchProgress&>(summary) = progress();
    summary.interrupted = shared.stopRequested();
    summary.loadsLeftBehind = stuckLoads;
    for (const std::unique_ptr<DeviceLane>& lane : mLanes) {
        lane->finish();
        addStages(summary.stages, lane->stages());
        summary.devices.push_back(lane->summary());
    }
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
    BatchRenderer* const devices[] = {&renderers};
    return runBatch(devices, inputs, options);
}

Result<BatchSummary> runBatch(std::span<BatchRenderer* const> devices,
                              std::span<const BatchInput> inputs,
                              const BatchOptions& options) {
    BatchRun run(devices, inputs, options);
    return run.run();
}

}  // namespace encore::batch
