#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <future>
#include <memory>
#include <mutex>
#include <vector>

#include "core/ThreadPool.h"

namespace encore {
namespace {

TEST(ThreadPoolTest, RunsEveryTaskBeforeWaitIdleReturns) {
    ThreadPool pool(3);
    EXPECT_EQ(pool.size(), 3u);
    std::atomic<int> sum{0};
    for (int i = 1; i <= 100; ++i) {
        pool.submit([&sum, i] { sum += i; });
    }
    pool.waitIdle();
    EXPECT_EQ(sum.load(), 5050);
}

// A task that never comes back (a read stuck in the kernel) is left out of waitIdle when the
// caller says so, and its pool is kept for the rest of the process instead of joined for ever.
TEST(ThreadPoolTest, AbandonedTasksAreNotWaitedFor) {
    auto pool = std::make_unique<ThreadPool>(2);
    auto stuck = std::make_shared<std::promise<void>>();
    std::shared_future<void> release = stuck->get_future().share();
    std::atomic<int> done{0};
    pool->submit([release] { release.wait(); });
    for (int i = 0; i < 10; ++i) {
        pool->submit([&done] { ++done; });
    }
    pool->waitIdle(1);  // Returns with the stuck task still running.
    EXPECT_EQ(done.load(), 10);
    ThreadPool::abandon(std::move(pool));
    EXPECT_EQ(pool, nullptr);
    stuck->set_value();  // Its thread may end now; the pool is never destroyed.
}

TEST(ThreadPoolTest, TasksMaySubmitTasks) {
    std::atomic<int> count{0};
    {
        ThreadPool pool(2);
        pool.submit([&] {
            ++count;
            pool.submit([&] { ++count; });
        });
        pool.waitIdle();
        EXPECT_EQ(count.load(), 2);
    }
}

TEST(ThreadPoolTest, DestructorRunsQueuedTasks) {
    std::atomic<int> count{0};
    {
        ThreadPool pool(1);
        for (int i = 0; i < 10; ++i) {
            pool.submit([&] { ++count; });
        }
    }
    EXPECT_EQ(count.load(), 10);
}

TEST(ThreadPoolTest, SubmitFirstRunsAheadOfQueuedTasks) {
    ThreadPool pool(1);
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    std::mutex mutex;
    std::vector<int> order;
    const auto record = [&](int value) {
        std::lock_guard lock(mutex);
        order.push_back(value);
    };
    pool.submit([released] { released.wait(); });  // Holds the only worker.
    pool.submit([&] { record(1); });
    pool.submit([&] { record(2); });
    pool.submitFirst([&] { record(0); });
    release.set_value();
    pool.waitIdle();
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2}));
}

TEST(ThreadPoolTest, ZeroThreadsMeansOnePerCore) {
    ThreadPool pool(0);
    EXPECT_GE(pool.size(), 1u);
}

// Workers run at the niceness asked for, added to the creating thread's; the creating thread
// keeps its own.
TEST(ThreadPoolTest, WorkersRunAtTheNicenessAskedFor) {
    errno = 0;
    const int base = getpriority(PRIO_PROCESS, id_t(gettid()));
    ASSERT_EQ(errno, 0);
    for (int niceness : {0, 7}) {
        std::mutex mutex;
        std::vector<int> seen;
        {
            ThreadPool pool(3, niceness);
            for (int i = 0; i < 6; ++i) {
                pool.submit([&] {
                    const int value = getpriority(PRIO_PROCESS, id_t(gettid()));
                    std::lock_guard lock(mutex);
                    seen.push_back(value);
                });
            }
            pool.waitIdle();
        }
        ASSERT_EQ(seen.size(), 6u);
        for (int value : seen) {
            EXPECT_EQ(value, std::min(base + niceness, 19)) << "niceness " << niceness;
        }
    }
    EXPECT_EQ(getpriority(PRIO_PROCESS, id_t(gettid())), base);
}

}  // namespace
}  // namespace encore
