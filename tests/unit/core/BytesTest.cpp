// copyBytes (core/Bytes.h): memcpy that accepts the null data() of empty vectors and spans for a
// zero-length copy (issue 32), and checks a destination span's length.

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "core/Bytes.h"

namespace encore {
namespace {

TEST(BytesTest, ZeroLengthCopyAcceptsNullPointers) {
    copyBytes(nullptr, nullptr, 0);
    std::vector<std::uint8_t> destination;
    const std::vector<std::uint8_t> source;
    ASSERT_EQ(destination.data(), nullptr);
    ASSERT_EQ(source.data(), nullptr);
    copyBytes(destination.data(), source.data(), source.size());
    copyBytes(destination, source);
    EXPECT_TRUE(destination.empty());
}

TEST(BytesTest, EmptySourceLeavesTheDestinationAsItWas) {
    std::vector<std::uint8_t> destination = {1, 2, 3};
    copyBytes(destination, std::span<const std::uint8_t>());
    copyBytes(destination.data() + 1, nullptr, 0);
    EXPECT_EQ(destination, (std::vector<std::uint8_t>{1, 2, 3}));
}

TEST(BytesTest, CopiesBytes) {
    const std::vector<std::uint8_t> source = {1, 2, 3, 4, 5};
    std::vector<std::uint8_t> destination(7, 0);
    copyBytes(destination.data() + 1, source.data(), 3);
    EXPECT_EQ(destination, (std::vector<std::uint8_t>{0, 1, 2, 3, 0, 0, 0}));
    copyBytes(std::span(destination).subspan(2), source);
    EXPECT_EQ(destination, (std::vector<std::uint8_t>{0, 1, 1, 2, 3, 4, 5}));
}

TEST(BytesTest, ShortDestinationSpanIsABug) {
    const std::vector<std::uint8_t> source = {1, 2, 3};
    std::vector<std::uint8_t> destination(2);
    EXPECT_DEATH(copyBytes(destination, source),
                 "destination \\(2 bytes\\) is shorter than the source \\(3 bytes\\)");
}

}  // namespace
}  // namespace encore
