#include "core/ThreadPool.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

namespace encore {

ThreadPool::ThreadPool(std::size_t threads, int niceness) {
    if (threads == 0) {
        threads = std::max(1u, std::thread::hardware_concurrency());
    }
    niceness = std::clamp(niceness, 0, 19);
    mWorkers.reserve(threads);
    for (std::size_t i = 0; i < threads; ++i) {
        mWorkers.emplace_back([this, niceness] {
            if (niceness > 0) {
                // Per thread on Linux (a thread id names the thread alone). Raising one's own
                // nice value needs no privilege; failure leaves the normal priority, which is
                // only slower.
                setpriority(PRIO_PROCESS, id_t(gettid()), niceness);
            }
            work();
        });
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
    }
    mWake.notify_all();
    for (std::thread& worker : mWorkers) {
        worker.join();
    }
}

void ThreadPool::abandon(std::unique_ptr<ThreadPool> pool) {
    static std::mutex mutex;
    // Reachable from here until the process ends, and never destroyed (not even at exit).
    static auto* abandoned = new std::vector<std::unique_ptr<ThreadPool>>();
    std::lock_guard lock(mutex);
    abandoned->push_back(std::move(pool));
}

void ThreadPool::submit(std::function<void()> task) {
    {
        std::lock_guard lock(mMutex);
        mTasks.push_back(std::move(task));
    }
    mWake.notify_one();
}

void ThreadPool::submitFirst(std::function<void()> task) {
    {
        std::lock_guard lock(mMutex);
        mTasks.push_front(std::move(task));
    }
    mWake.notify_one();
}

void ThreadPool::waitIdle(std::size_t abandoned) {
    std::unique_lock lock(mMutex);
    mIdle.wait(lock, [&] { return mTasks.empty() && mRunning <= abandoned; });
}

void ThreadPool::work() {
    std::unique_lock lock(mMutex);
    while (true) {
        mWake.wait(lock, [this] { return mStopping || !mTasks.empty(); });
        if (mTasks.empty()) {
            return;  // Stopping, and nothing left to run.
        }
        std::function<void()> task = std::move(mTasks.front());
        mTasks.pop_front();
        ++mRunning;
        lock.unlock();
        task();
        task = nullptr;  // Release what the task captured before reporting idle.
        lock.lock();
        --mRunning;
        if (mTasks.empty()) {
            mIdle.notify_all();  // waitIdle may leave abandoned tasks running.
        }
    }
}

}  // namespace encore
