#pragma once

// Work handed to a thread pool that the thread which handed it over may also do, or give up,
// whichever comes first: only the thread that claims the task runs it. The batch's staging copies
// (render/StagedImages, render/StagedGeometry) use it: the device thread copies what the pool has
// not started once it needs the bytes, and gives up what is left when the staging goes away.
//
// The tasks of one owner share a `Finished`, which the pool's tasks hold too (they may run after
// the owner is gone, and then find their task claimed).

#include <atomic>
#include <condition_variable>
#include <mutex>

namespace encore {

class ClaimedTask {
  public:
    struct Finished {
        std::mutex mutex;
        std::condition_variable condition;
    };

    // Runs `work` unless another thread has claimed the task.
    template <typename Work>
    void run(Finished& finished, Work&& work) {
        if (mClaimed.exchange(true)) {
            return;
        }
        work();
        {
            std::lock_guard lock(finished.mutex);
            mDone = true;
        }
        finished.condition.notify_all();
    }
    // Waits until the task has run: call it after run() (which claimed it, or found it claimed
    // by a thread that runs it).
    void wait(Finished& finished) const {
        std::unique_lock lock(finished.mutex);
        finished.condition.wait(lock, [&] { return mDone; });
    }
    // Claims the task so that it never runs; waits for it when a thread has it already.
    void cancel(Finished& finished) {
        if (mClaimed.exchange(true)) {
            wait(finished);
        }
    }

  private:
    std::atomic<bool> mClaimed{false};
    bool mDone = false;  // Guarded by Finished::mutex.
};

}  // namespace encore
