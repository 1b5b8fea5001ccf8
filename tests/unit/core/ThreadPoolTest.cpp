#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <mutex>
#include <vector>

#include "encore/core/ThreadPool.h"

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

}  // namespace
}  // namespace encore
