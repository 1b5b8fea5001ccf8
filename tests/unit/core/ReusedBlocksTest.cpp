#include "encore/core/ReusedBlocks.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace encore {
namespace {

constexpr std::size_t kMiB = std::size_t(1) << 20;

// The shelf is the process's: the tests compare its counts before and after.
TEST(ReusedBlocksTest, AFreedBlockServesTheNextVectorOfItsSizeClass) {
    const ReusedBlockCounts before = reusedBlockCounts();
    const std::uint8_t* first = nullptr;
    {
        ReusedBytes bytes(3 * kMiB);
        first = bytes.data();
        bytes[0] = 1;
    }
    const ReusedBlockCounts kept = reusedBlockCounts();
    EXPECT_EQ(kept.created, before.created + 1);
    EXPECT_EQ(kept.keptBytes, before.keptBytes + 3 * kMiB);
    {
        ReusedBytes again(3 * kMiB - 1000);  // Within an eighth: the same class.
        EXPECT_EQ(again.data(), first);
    }
    const ReusedBlockCounts after = reusedBlockCounts();
    EXPECT_EQ(after.taken, before.taken + 2);
    EXPECT_EQ(after.created, before.created + 1);
    EXPECT_EQ(after.createdBytes, before.createdBytes + 3 * kMiB);
}

TEST(ReusedBlocksTest, OtherSizeClassesAndSmallVectorsGetTheirOwn) {
    const ReusedBlockCounts before = reusedBlockCounts();
    { ReusedBytes large(5 * kMiB); }
    { ReusedBytes larger(7 * kMiB); }  // Past 5 MiB's class (4 MiB + n x 512 KiB).
    { ReusedBytes small(kReusedBlockBytes - 1); }
    const ReusedBlockCounts after = reusedBlockCounts();
    EXPECT_EQ(after.taken, before.taken + 2);
    EXPECT_EQ(after.created, before.created + 2);
}

TEST(ReusedBlocksTest, BlocksPastTheLimitAreFreed) {
    const std::uint64_t limit = reusedBlockLimit();
    setReusedBlockLimit(0);
    EXPECT_EQ(reusedBlockCounts().keptBytes, 0u);
    const ReusedBlockCounts before = reusedBlockCounts();
    { ReusedBytes bytes(2 * kMiB); }
    { ReusedBytes bytes(2 * kMiB); }
    const ReusedBlockCounts after = reusedBlockCounts();
    EXPECT_EQ(after.keptBytes, 0u);
    EXPECT_EQ(after.created, before.created + 2);
    setReusedBlockLimit(limit);
}

TEST(ReusedBlocksTest, CopiesAndComparisonsKeepTheBytes) {
    ReusedBytes bytes(kReusedBlockBytes, 7);
    bytes.back() = 9;
    const ReusedBytes copy = bytes;
    EXPECT_EQ(copy, bytes);
    std::vector<std::uint8_t> plain(kReusedBlockBytes, 7);
    EXPECT_FALSE(copy == plain);
    plain.back() = 9;
    EXPECT_EQ(copy, plain);
    EXPECT_EQ(plain, copy);
}

}  // namespace
}  // namespace encore
