#include "render/animation/KeyframeStore.h"

#include <gtest/gtest.h>

#include <vector>

namespace encore::render {
namespace {

TEST(KeyframeStoreTest, EqualRunsAreStoredOnce) {
    KeyframeStore store;
    const std::vector<float> times = {0.0f, 0.5f, 1.0f};
    const std::vector<float> values = {1.0f, 2.0f, 3.0f, 4.0f};
    EXPECT_EQ(store.add(times), 0u);
    EXPECT_EQ(store.add(values), 3u);
    // The same data again, from other vectors: the first copies.
    EXPECT_EQ(store.add(std::vector<float>(times)), 0u);
    EXPECT_EQ(store.add(std::vector<float>(values)), 3u);
    EXPECT_EQ(store.size(), 7u);
    EXPECT_EQ(store.floats(), (std::vector<float>{0.0f, 0.5f, 1.0f, 1.0f, 2.0f, 3.0f, 4.0f}));
}

TEST(KeyframeStoreTest, RunsThatDifferInLengthOrOneBitAreKeptApart) {
    KeyframeStore store;
    EXPECT_EQ(store.add(std::vector<float>{1.0f, 2.0f}), 0u);
    EXPECT_EQ(store.add(std::vector<float>{1.0f, 2.0f, 3.0f}), 2u);  // A longer run.
    EXPECT_EQ(store.add(std::vector<float>{1.0f}), 5u);              // A prefix is not shared.
    EXPECT_EQ(store.add(std::vector<float>{0.0f}), 6u);
    EXPECT_EQ(store.add(std::vector<float>{-0.0f}), 7u);  // Equal as numbers, not as bits.
    EXPECT_EQ(store.size(), 8u);
}

TEST(KeyframeStoreTest, AppendedRunsAreNeverShared) {
    KeyframeStore store;
    const std::vector<float> weights = {0.25f, 0.75f};
    EXPECT_EQ(store.append(weights), 0u);
    EXPECT_EQ(store.append(weights), 2u);
    EXPECT_EQ(store.add(weights), 4u);  // Appended runs are not candidates for sharing.
    EXPECT_EQ(store.add(weights), 4u);
    EXPECT_EQ(store.take().size(), 6u);
}

}  // namespace
}  // namespace encore::render
