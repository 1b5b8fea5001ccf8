#pragma once

// A fixed set of worker threads running submitted tasks in submission order. Used by pipelines
// that keep CPU stages (parsing, decoding, encoding) busy beside a GPU thread.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace encore {

class ThreadPool {
  public:
    // `threads` workers; 0 means one per hardware thread. A positive `niceness` lowers the
    // workers' scheduling priority by that much (Linux thread nice values, 1..19): when the
    // workers fill every core, a thread at normal priority that feeds a GPU still gets a core
    // as soon as it has work.
    explicit ThreadPool(std::size_t threads, int niceness = 0);
    // Runs every task already submitted, then joins the workers.
    ~ThreadPool();

    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Queues `task`. Tasks must not throw (the library reports errors as values).
    void submit(std::function<void()> task);
    // Queues `task` ahead of every task not yet started: for work that another thread is about
    // to wait for.
    void submitFirst(std::function<void()> task);
    // Blocks until every submitted task has finished but `abandoned` (tasks known never to come
    // back, such as a read stuck in the kernel: the caller no longer waits for them).
    void waitIdle(std::size_t abandoned = 0);
    std::size_t size() const { return mWorkers.size(); }
    // Keeps `pool` for the rest of the process, never destroyed: for a pool that runs a task
    // which never comes back (its destructor would wait for it for ever). The abandoned task and
    // what it captured stay; its idle threads sleep.
    static void abandon(std::unique_ptr<ThreadPool> pool);

  private:
    void work();

    std::mutex mMutex;
    std::condition_variable mWake;  // A task was queued, or the pool is stopping.
    std::condition_variable mIdle;  // The last running task finished.
    std::deque<std::function<void()>> mTasks;
    std::size_t mRunning = 0;
    bool mStopping = false;
    std::vector<std::thread> mWorkers;
};

}  // namespace encore
