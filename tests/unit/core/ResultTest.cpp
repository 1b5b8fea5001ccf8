#include <gtest/gtest.h>

#include "encore/core/Result.h"

namespace encore {
namespace {

Result<int> parsePositive(int value) {
    if (value <= 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "Value must be positive (" + std::to_string(value) + ").");
    }
    return value;
}

Result<int> doubled(int value) {
    auto parsed = parsePositive(value);
    if (!parsed) {
        return parsed.error().withContext("Doubling");
    }
    return *parsed * 2;
}

Result<void> check(int value) {
    ENCORE_TRY(parsePositive(value));
    return {};
}

TEST(ResultTest, CarriesValueOrError) {
    auto good = doubled(21);
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(*good, 42);

    auto bad = doubled(-3);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(bad.error().message, "Doubling: Value must be positive (-3).");
}

TEST(ResultTest, TryPropagatesErrors) {
    EXPECT_TRUE(check(1).ok());
    auto failed = check(0);
    ASSERT_FALSE(failed.ok());
    EXPECT_EQ(failed.error().message, "Value must be positive (0).");
}

TEST(ResultTest, EveryCodeHasAName) {
    EXPECT_EQ(errorCodeName(ErrorCode::FileNotFound), "file not found");
    EXPECT_EQ(errorCodeName(ErrorCode::NoAdapter), "no adapter");
}

}  // namespace
}  // namespace encore
