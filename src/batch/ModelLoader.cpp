#include "batch/ModelLoader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "core/Elapsed.h"
#include "scene/LoadBudget.h"

namespace encore::batch {

namespace {

// ENCORE_TEST_STALL_LOAD=TEXT: the load of a model whose path contains TEXT never returns and
// checks nothing, as a read stuck in the kernel (a hung network mount) would; for the tests of
// ModelLoader::finish's abandonment.
void stallForTests(const std::filesystem::path& path) {
    const char* text = std::getenv("ENCORE_TEST_STALL_LOAD");
    if (text == nullptr || *text == '\0' || path.string().find(text) == std::string::npos) {
        return;
    }
    while (true) {
        std::this_thread::sleep_for(std::chrono::hours(1));
    }
}

}  // namespace

// One load's view of the loader's memory limit: what it holds counts beside the scenes loaded
// ahead and the other loads; past the limit it waits, unless the loader stops or it is the oldest
// load running while no scene waits to be taken (the load a taker waits for is never held).
// Scenes loaded ahead and not yet taken hold back even the oldest: otherwise, with a taker busy
// elsewhere, each load in turn became the oldest, went on and joined them, to the limit times
// the loads running. A load never takes the pool's last thread into a wait: a taker that waits
// for the pool's other work (a batch's device thread for its encodes, to free a read-back slot)
// before it takes the next scene would otherwise wait for ever.
class ModelLoader::Budget final : public scene::LoadBudget {
  public:
    Budget(ModelLoader& loader,
           std::shared_ptr<Presence> presence,
           std::size_t order,
           const std::atomic<bool>& cancel)
        : mLoader(loader), mPresence(std::move(presence)), mOrder(order), mCancel(cancel) {}

    Result<void> holding(std::uint64_t bytes) override {
        std::unique_lock<std::mutex> lock;
        {
            // Not held while waiting: the other loads' tasks take it to finish.
            std::lock_guard present(mPresence->mutex);
            if (mPresence->gone) {
                return {};  // A load abandoned to the kernel that came back: nothing to share.
            }
            lock = std::unique_lock(mLoader.mMutex);
            if (mLoader.mStopped) {
                return {};  // finish() may destroy the loader once its grace ends.
            }
        }
        bool waited = false;
        while (true) {
            const auto found = mLoader.mLoading.find(mOrder);
            if (found == mLoader.mLoading.end()) {
                mLoader.mLoadsWaiting -= waited ? 1 : 0;
                return {};  // Abandoned at the time limit: it stops at its next check.
            }
            found->second.bytes = bytes;
            std::uint64_t total = mLoader.mBytesHeld;
            const RunningLoad* oldest = nullptr;
            for (const auto& [order, load] : mLoader.mLoading) {
                total += load.bytes;
                if (!oldest && load.start) {
                    oldest = &load;
                }
            }
            mLoader.mPeakBytes = std::max(mLoader.mPeakBytes, total);
            const bool awaited = oldest == &found->second && !mLoader.nextLoaded();
            // The last of the pool's threads not waiting here goes on: the pool's other tasks
            // (the batch's encodes, which the taker may be waiting for) need one.
            const bool lastThread = !waited && mLoader.mLoadsWaiting + 1 >= mLoader.mPool->size();
            if (total <= mLoader.mMemoryLimit || awaited || lastThread || mLoader.mStopped ||
                mCancel.load(std::memory_order_relaxed)) {
                mLoader.mLoadsWaiting -= waited ? 1 : 0;
                return {};
            }
            if (!waited) {
                ++mLoader.mBudgetWaits;
                ++mLoader.mLoadsWaiting;
                waited = true;
            }
            // Woken as loads finish and scenes are released; the timeout rechecks the cancel.
            mLoader.mLoaded.wait_for(lock, std::chrono::milliseconds(50));
        }
    }

  private:
    ModelLoader& mLoader;
    std::shared_ptr<Presence> mPresence;
    std::size_t mOrder;
    const std::atomic<bool>& mCancel;
};

ModelLoader::ModelLoader(ThreadPool& pool,
                         std::span<const BatchInput> inputs,
                         const scene::LoadOptions& options,
                         std::uint64_t memoryLimitBytes,
                         std::size_t ahead,
                         Order order,
                         double timeoutSeconds)
    : mPool(&pool),
      mInputs(inputs),
      mOptions(options),
      mMemoryLimit(memoryLimitBytes),
      mAhead(std::max<std::size_t>(ahead, 1)),
      mOrder(order),
      mTimeoutSeconds(timeoutSeconds) {
    std::lock_guard lock(mMutex);
    startLoads();
}

void ModelLoader::startLoads() {
    // The scenes held count against the limit; a load's size is unknown until it ends, so the
    // limit may be passed by the loads running when it is reached. With nothing loaded or
    // loading ahead of the GPU thread, one load always starts, whatever the scene the GPU
    // thread holds: models larger than the limit still render, one at a time.
    while (!mStopped && mNextToStart < mInputs.size() && mLoading.size() < mAhead &&
           (mBytesHeld < mMemoryLimit || (mReady.empty() && mLoading.empty()))) {
        const std::size_t order = mNextToStart++;
        ++mRunning;
        auto cancel = std::make_shared<std::atomic<bool>>(false);
        mLoading.emplace(order, RunningLoad{std::nullopt, cancel});
        mPool->submit([this, order, cancel, path = mInputs[order].path, presence = mPresence] {
            LoadedModel loaded;
            scene::LoadOptions options;
            const auto start = Clock::now();
            {
                std::lock_guard present(presence->mutex);
                if (presence->gone) {
                    return;  // Queued when the loader finished: nothing to load for.
                }
                // The time limit counts from here, not from the wait in the pool's queue.
                std::lock_guard lock(mMutex);
                mLoading.at(order).start = start;
                options = mOptions;
            }
            const double cpuStart = threadCpuSeconds();
            loaded.order = order;
            options.cancel = cancel.get();
            Budget budget(*this, presence, order, *cancel);
            options.budget = &budget;
            stallForTests(path);
            loaded.scene = loadModelFile(path, options, loaded.facts);
            if (loaded.scene) {
                loaded.bytes = scene::decodedBytes(*loaded.scene);
            }
            loaded.seconds = secondsSince(start);
            loaded.cpuSeconds = threadCpuSeconds() - cpuStart;
            std::lock_guard present(presence->mutex);
            if (presence->gone) {
                return;  // Abandoned in the kernel by a loader that is gone since.
            }
            std::lock_guard lock(mMutex);
            --mRunning;
            if (mLoading.erase(order) == 0) {
                // Abandoned at the time limit: its model was handed over as failed.
                mLoaded.notify_all();
                return;
            }
            mBytesHeld += loaded.bytes;
            mReady.emplace(order, std::move(loaded));
            mLoaded.notify_all();
            startLoads();
        });
    }
}

void ModelLoader::expireLoads() {
    if (mTimeoutSeconds <= 0.0) {
        return;
    }
    const auto now = Clock::now();
    bool expired = false;
    for (auto it = mLoading.begin(); it != mLoading.end();) {
        const double seconds =
            it->second.start ? std::chrono::duration<double>(now - *it->second.start).count() : 0.0;
        if (seconds < mTimeoutSeconds) {
            ++it;
            continue;
        }
        it->second.cancel->store(true, std::memory_order_relaxed);
        char limit[32];
        std::snprintf(limit, sizeof(limit), "%g", mTimeoutSeconds);
        LoadedModel abandoned;
        abandoned.order = it->first;
        abandoned.timedOut = true;
        abandoned.seconds = seconds;
        abandoned.scene = makeError(ErrorCode::LimitExceeded,
                                    mInputs[it->first].path.string() +
                                        ": Loading took longer than the model time limit (" +
                                        limit + " s); the model was abandoned.");
        mReady.emplace(it->first, std::move(abandoned));
        it = mLoading.erase(it);
        expired = true;
    }
    if (expired) {
        mLoaded.notify_all();
        startLoads();
    }
}

ModelLoader::Clock::duration ModelLoader::nextExpiry(Clock::duration longest) const {
    if (mTimeoutSeconds <= 0.0 || mLoading.empty()) {
        return longest;
    }
    const auto limit =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(mTimeoutSeconds));
    Clock::time_point earliest = Clock::time_point::max();
    for (const auto& [order, load] : mLoading) {
        if (load.start) {
            earliest = std::min(earliest, *load.start + limit);
        }
    }
    if (earliest == Clock::time_point::max()) {
        return longest;  // None started yet.
    }
    // A little past it, so that the load has passed the limit when the taker wakes.
    const auto until = earliest - Clock::now() + std::chrono::milliseconds(1);
    return std::min(longest, std::max(until, Clock::duration::zero()));
}

bool ModelLoader::nextLoaded() const {
    return mOrder == Order::InOrder ? mReady.contains(mNextToTake) : !mReady.empty();
}

bool ModelLoader::exhausted() {
    std::lock_guard lock(mMutex);
    return mStopped || mTaken >= mInputs.size();
}

void ModelLoader::waitForNext(int milliseconds) {
    std::unique_lock lock(mMutex);
    const auto deadline = Clock::now() + std::chrono::milliseconds(milliseconds);
    while (!mStopped && !nextLoaded() && Clock::now() < deadline) {
        mLoaded.wait_for(lock, nextExpiry(deadline - Clock::now()));
        expireLoads();
    }
}

std::optional<LoadedModel> ModelLoader::takeLoaded() {
    expireLoads();
    if (mStopped || !nextLoaded()) {
        return std::nullopt;
    }
    auto node =
        mOrder == Order::InOrder ? mReady.extract(mNextToTake++) : mReady.extract(mReady.begin());
    ++mTaken;
    return std::move(node.mapped());
}

std::optional<LoadedModel> ModelLoader::tryTake() {
    std::lock_guard lock(mMutex);
    return takeLoaded();
}

std::optional<LoadedModel> ModelLoader::take() {
    std::unique_lock lock(mMutex);
    while (!mStopped && mTaken < mInputs.size() && !nextLoaded()) {
        mLoaded.wait_for(lock, nextExpiry(std::chrono::seconds(1)));
        expireLoads();
    }
    return takeLoaded();
}

void ModelLoader::release(std::uint64_t bytes) {
    std::lock_guard lock(mMutex);
    mBytesHeld -= std::min(bytes, mBytesHeld);
    mLoaded.notify_all();  // Loads waiting for room.
    startLoads();
}

std::uint64_t ModelLoader::peakBytes() {
    std::lock_guard lock(mMutex);
    return mPeakBytes;
}

std::size_t ModelLoader::budgetWaits() {
    std::lock_guard lock(mMutex);
    return mBudgetWaits;
}

void ModelLoader::stop() {
    std::lock_guard lock(mMutex);
    mStopped = true;
    mLoaded.notify_all();
}

std::size_t ModelLoader::finish() {
    stop();
    std::unique_lock lock(mMutex);
    for (auto& [order, load] : mLoading) {
        load.cancel->store(true, std::memory_order_relaxed);  // Their results would be dropped.
    }
    mLoaded.wait_for(lock, std::chrono::duration<double>(kStuckLoadGraceSeconds),
                     [this] { return mRunning == 0; });
    mReady.clear();
    return mRunning;
}

ModelLoader::~ModelLoader() {
    std::lock_guard present(mPresence->mutex);
    mPresence->gone = true;
}

}  // namespace encore::batch
