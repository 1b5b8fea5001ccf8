#include <gtest/gtest.h>

#include <atomic>

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

TEST(ThreadPoolTest, ZeroThreadsMeansOnePerCore) {
    ThreadPool pool(0);
    EXPECT_GE(pool.size(), 1u);
}

}  // namespace
}  // namespace encore
