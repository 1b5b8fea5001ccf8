// The structure-aware mutation of the fuzzers (fuzz/NumberMutator.cpp) on documents whose numbers
// are already at the edges of what it computes with: the fuzzer runs it under UBSan, where any
// overflow stops the run as a crash of the mutator, not of the loader.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "NumberMutator.h"

namespace encore::fuzz {
namespace {

using Json = nlohmann::json;

// Every number of a parsed document.
void collect(const Json& json, std::vector<Json>& numbers) {
    if (json.is_number()) {
        numbers.push_back(json);
    } else if (json.is_structured()) {
        for (const auto& child : json) {
            collect(child, numbers);
        }
    }
}

std::string mutated(const std::string& document, unsigned seed) {
    std::vector<std::uint8_t> bytes(document.begin(), document.end());
    bytes.resize(document.size() + 4096);
    const std::size_t size = mutateNumbers(bytes.data(), document.size(), bytes.size(), seed);
    return std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(size));
}

TEST(NumberMutatorTest, NumbersNearTheInt64LimitsNeverWrapAround) {
    // Positive numbers only, so a negative result is one of the mutator's own negatives or an
    // integer that wrapped (twice 6e18 is past 2^63).
    const std::string document =
        R"({"asset":{"version":"2.0"},"accessors":[{"count":6000000000000000000,)"
        R"("byteOffset":9000000000000000000,"componentType":5126,"max":[4611686018427387904]}]})";
    const std::set<std::int64_t> ownNegatives = {
        -1, -2, -3, -4, std::int64_t(std::numeric_limits<std::int32_t>::min())};
    int parsed = 0;
    for (unsigned seed = 0; seed < 4000; ++seed) {
        const std::string text = mutated(document, seed);
        const Json json = Json::parse(text, nullptr, false);
        if (text.empty() || json.is_discarded()) {
            continue;  // byte-level by choice, or a literal NaN / Infinity that is not JSON
        }
        ++parsed;
        std::vector<Json> numbers;
        collect(json, numbers);
        for (const Json& number : numbers) {
            if (number.is_number_integer() && !number.is_number_unsigned() &&
                number.get<std::int64_t>() < 0) {
                EXPECT_TRUE(ownNegatives.count(number.get<std::int64_t>()))
                    << "seed " << seed << ": " << text;
            }
        }
    }
    EXPECT_GT(parsed, 3000);
}

TEST(NumberMutatorTest, CrossOverCopiesNumbersAtTheSameKeys) {
    const std::string first = R"({"accessors":[{"count":3,"byteOffset":0}]})";
    const std::string second = R"({"accessors":[{"count":18446744073709551615}]})";
    std::vector<std::uint8_t> out(1024);
    int copied = 0;
    for (unsigned seed = 0; seed < 64; ++seed) {
        const std::size_t size =
            crossOverNumbers(reinterpret_cast<const std::uint8_t*>(first.data()), first.size(),
                             reinterpret_cast<const std::uint8_t*>(second.data()), second.size(),
                             out.data(), out.size(), seed);
        ASSERT_GT(size, 0u);
        const Json json = Json::parse(out.begin(), out.begin() + std::ptrdiff_t(size));
        const Json& accessor = json["accessors"][0];
        EXPECT_EQ(accessor["byteOffset"], 0);  // no "byteOffset" in the second document
        copied += accessor["count"] == std::numeric_limits<std::uint64_t>::max();
    }
    EXPECT_GT(copied, 0);
}

}  // namespace
}  // namespace encore::fuzz
