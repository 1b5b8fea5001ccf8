#pragma once

// Loads a batch's models on the thread pool ahead of the GPU thread, which takes them in order.
// Loads start while fewer than `ahead` are running and the scenes loaded but not yet released
// stay under the memory limit, so a collection of any size needs the memory of a few models.
//
// A load that runs past its time limit is abandoned: the next take hands its model over as failed
// (LoadedModel::timedOut) and another load starts in its place. Its thread cannot be stopped
// from outside; the load is told to cancel (scene::LoadOptions::cancel) and stops at its next
// check, its result dropped, and finish() waits for it (the pool runs it to that check).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "batch/ModelMetadata.h"
#include "core/ThreadPool.h"
#include "encore/batch/BatchInputs.h"
#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::batch {

struct LoadedModel {
    std::size_t order = 0;  // Position in the load order.
    Result<scene::SceneData> scene = makeError(ErrorCode::InvalidArgument, "Not loaded.");
    std::uint64_t bytes = 0;  // What the scene holds in memory (scene::decodedBytes).
    ModelFacts facts;         // Its file's size and digest, and what the scene holds.
    bool timedOut = false;    // Abandoned at the time limit: `scene` says so.
    double seconds = 0.0;
    double cpuSeconds = 0.0;  // The loading thread's CPU time.
};

class ModelLoader {
  public:
    // Loads `inputs` (which must outlive the loader) in their order. Call finish() before the
    // loader goes away. A load stuck in the kernel (a read from a hung network mount) may
    // outlive it: its task then drops its result without touching the loader.
    // InOrder: models are taken in the order of `inputs`. AsLoaded: whichever has loaded, the
    // earliest first, so that one slow load holds up none of several takers (device threads).
    enum class Order { InOrder, AsLoaded };

    ModelLoader(ThreadPool& pool,
                std::span<const BatchInput> inputs,
                const scene::LoadOptions& options,
                std::uint64_t memoryLimitBytes,
                std::size_t ahead,
                Order order = Order::InOrder,
                double timeoutSeconds = 0.0);  // > 0: each load's time limit.

    // Whether every model was taken, or stop() was called.
    bool exhausted();
    // The next model (as Order says) when it has loaded; nullopt otherwise, or when every model
    // was taken or stop() was called. Any thread may call it.
    std::optional<LoadedModel> tryTake();
    // The same, waiting for the next model to load; nullopt when every model was taken or stop()
    // was called.
    std::optional<LoadedModel> take();
    // Waits up to `milliseconds` for the next model to load.
    void waitForNext(int milliseconds);
    // The GPU thread is done with a scene of `bytes`: more loads may start.
    void release(std::uint64_t bytes);
    // The most the scenes held and the loads in progress held decoded at once, as the loads
    // reported it, and how many times a load waited for room. The limit is shared: a load whose
    // bytes would pass it waits, unless it is the oldest running and no scene waits to be taken.
    std::uint64_t peakBytes();
    std::size_t budgetWaits();
    // Starts no more loads.
    void stop();
    // Cancels the loads still running and waits for them (their results are dropped), up to
    // kStuckLoadGraceSeconds: a cancelled load stops at its next check, one that has not by then
    // is stuck where no check comes (in the kernel) and is abandoned to its thread. Returns the
    // loads abandoned so: the pool's threads that run them may never come back.
    std::size_t finish();
    ~ModelLoader();

    static constexpr double kStuckLoadGraceSeconds = 5.0;

  private:
    using Clock = std::chrono::steady_clock;
    // A load on the pool, until it finishes or is abandoned.
    struct RunningLoad {
        std::optional<Clock::time_point> start;     // Once a pool thread runs it.
        std::shared_ptr<std::atomic<bool>> cancel;  // Shared with its task.
        std::uint64_t bytes = 0;                    // Decoded so far (its LoadBudget's last word).
    };
    class Budget;  // The memory limit, as the loads see it (scene::LoadBudget).

    // What a load's task shares with the loader: set when the loader is gone, so that a task
    // that comes back from a stuck read (or starts after finish) drops its model.
    struct Presence {
        std::mutex mutex;
        bool gone = false;
    };

    void startLoads();  // Called with mMutex held.
    // Abandons the loads past the time limit, handing them over as failed. With mMutex held.
    void expireLoads();
    // How long a waiting taker may sleep before a load may pass the limit (at most `longest`).
    Clock::duration nextExpiry(Clock::duration longest) const;
    // Called with mMutex held.
    bool nextLoaded() const;
    std::optional<LoadedModel> takeLoaded();

    ThreadPool* mPool;
    std::span<const BatchInput> mInputs;
    scene::LoadOptions mOptions;
    std::uint64_t mMemoryLimit;
    std::size_t mAhead;
    Order mOrder;
    double mTimeoutSeconds;

    std::mutex mMutex;
    std::condition_variable mLoaded;
    std::map<std::size_t, LoadedModel> mReady;
    std::size_t mNextToStart = 0;
    std::size_t mNextToTake = 0;  // InOrder: the next to take.
    std::size_t mTaken = 0;
    std::map<std::size_t, RunningLoad> mLoading;  // By order; counts against `ahead`.
    std::size_t mRunning = 0;  // Tasks on the pool, abandoned ones too: finish() waits for them.
    std::uint64_t mBytesHeld = 0;  // Loaded, not yet released.
    std::uint64_t mPeakBytes = 0;
    std::size_t mBudgetWaits = 0;
    std::size_t mLoadsWaiting = 0;  // Loads waiting in Budget::holding now.
    bool mStopped = false;
    std::shared_ptr<Presence> mPresence = std::make_shared<Presence>();
};

}  // namespace encore::batch
