#include <gtest/gtest.h>
#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "image/RunLengthDeflate.h"

namespace encore::image {
namespace {

struct Case {
    std::string name;
    std::vector<std::uint8_t> data;
};

// A linear congruential generator: the same bytes on every platform.
class Random {
  public:
    explicit Random(std::uint32_t seed) : mState(seed) {}
    std::uint32_t next() {
        mState = mState * 1664525u + 1013904223u;
        return mState >> 8;
    }

  private:
    std::uint32_t mState;
};

// Inputs at the edges of the tokenizer: no data, one byte, one value throughout, no two equal
// neighbours (all literals), runs of every length around deflate's 3-byte minimum and 258-byte
// maximum (259 leaves one byte, 260 two, 261 a second run), a run at the very end, and data
// shaped like a Paeth-filtered view: rows of zeros, short runs and small residuals.
std::vector<Case> cases() {
    std::vector<Case> all;
    all.push_back({"empty", {}});
    all.push_back({"one byte", {42}});
    all.push_back({"two equal bytes", {9, 9}});
    all.push_back({"all zero", std::vector<std::uint8_t>(1 << 20, 0)});
    std::vector<std::uint8_t> distinct(70000);
    for (std::size_t i = 0; i < distinct.size(); ++i) {
        distinct[i] = std::uint8_t(i * 7 + i / 256);
    }
    all.push_back({"no equal neighbours", distinct});
    for (std::size_t length : {2, 3, 4, 257, 258, 259, 260, 261, 262, 516, 517, 518, 519}) {
        std::vector<std::uint8_t> data{1};
        data.insert(data.end(), length, 5);
        all.push_back({"run of " + std::to_string(length) + " at the end", data});
        data.push_back(2);
        all.push_back({"run of " + std::to_string(length), data});
    }
    std::vector<std::uint8_t> lengths;
    for (std::size_t length = 1; length <= 600; ++length) {
        lengths.insert(lengths.end(), length, std::uint8_t(length % 7));
    }
    all.push_back({"runs 1 to 600", lengths});
    Random random(7);
    std::vector<std::uint8_t> view;
    for (int row = 0; row < 300; ++row) {
        view.push_back(4);  // The filter type.
        const bool background = row < 60 || row > 240;
        std::size_t column = 0;
        while (column < 1024) {
            const std::uint32_t draw = random.next();
            std::size_t span = 1;
            if (background) {
                span = 1024;
            } else if (draw % 4 == 0) {
                span = 1 + (draw >> 4) % 40;
            }
            span = std::min(span, 1024 - column);
            const std::uint8_t residual =
                background || draw % 3 != 0 ? 0 : std::uint8_t((draw >> 12) % 9);
            view.insert(view.end(), span, residual);
            column += span;
        }
    }
    all.push_back({"filtered view", view});
    std::vector<std::uint8_t> noise(100000);
    for (auto& byte : noise) {
        byte = std::uint8_t(random.next());
    }
    all.push_back({"noise", noise});
    return all;
}

std::vector<std::uint8_t> compress(const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> stream(runLengthZlibBound(data.size()));
    stream.resize(runLengthZlib(data, stream.data()));
    return stream;
}

// Every stream inflates to its data with zlib (which refuses incomplete or over-subscribed
// codes) and with libdeflate.
TEST(RunLengthDeflateTest, InflatesToItsDataWithZlibAndLibdeflate) {
    libdeflate_decompressor* decompressor = libdeflate_alloc_decompressor();
    ASSERT_NE(decompressor, nullptr);
    for (const Case& test : cases()) {
        SCOPED_TRACE(test.name);
        const std::vector<std::uint8_t> stream = compress(test.data);
        ASSERT_GT(stream.size(), 6u);
        std::vector<std::uint8_t> inflated(test.data.size() + 1);
        uLongf size = uLongf(inflated.size());
        ASSERT_EQ(uncompress(inflated.data(), &size, stream.data(), uLong(stream.size())), Z_OK);
        ASSERT_EQ(size, test.data.size());
        EXPECT_TRUE(std::equal(test.data.begin(), test.data.end(), inflated.begin()));
        std::vector<std::uint8_t> again(test.data.size() + 1, 0xee);
        std::size_t inSize = 0;
        std::size_t outSize = 0;
        ASSERT_EQ(libdeflate_zlib_decompress_ex(decompressor, stream.data(), stream.size(),
                                                again.data(), again.size(), &inSize, &outSize),
                  LIBDEFLATE_SUCCESS);
        EXPECT_EQ(inSize, stream.size());
        ASSERT_EQ(outSize, test.data.size());
        EXPECT_TRUE(std::equal(test.data.begin(), test.data.end(), again.begin()));
    }
    libdeflate_free_decompressor(decompressor);
}

// The streams are byte for byte those of the first implementation (which tokenized the data
// twice and wrote codes one at a time): a dataset written again gives the same PNG files. The
// sizes and CRC-32s below are that implementation's.
TEST(RunLengthDeflateTest, StreamsAreUnchanged) {
    struct Expected {
        std::size_t size;
        std::uint32_t crc;
    };
    const std::vector<Expected> expected = {
        {18, 0x765f57c0u},      // empty
        {19, 0xb564e898u},      // one byte
        {19, 0x816dee5cu},      // two equal bytes
        {1038, 0x6eac1e97u},    // all zero
        {70068, 0x815193f2u},   // no equal neighbours
        {20, 0x20352d9au},      // run of 2 at the end
        {21, 0xc66807edu},      // run of 2
        {21, 0x6dc27127u},      // run of 3 at the end
        {21, 0xaadd55a2u},      // run of 3
        {21, 0x6587417bu},      // run of 4 at the end
        {22, 0x9196af0eu},      // run of 4
        {23, 0x702f8694u},      // run of 257 at the end
        {24, 0xd484fc76u},      // run of 257
        {23, 0x16c7ac72u},      // run of 258 at the end
        {24, 0x71bd7b7bu},      // run of 258
        {22, 0xa4768646u},      // run of 259 at the end
        {23, 0x2538b148u},      // run of 259
        {22, 0x6afae9d9u},      // run of 260 at the end
        {23, 0xac23a855u},      // run of 260
        {23, 0x1609412cu},      // run of 261 at the end
        {23, 0x487baa54u},      // run of 261
        {23, 0x69f07d7bu},      // run of 262 at the end
        {24, 0xe324fe0bu},      // run of 262
        {24, 0x39937a1cu},      // run of 516 at the end
        {24, 0x95473ce3u},      // run of 516
        {22, 0x446bf0d9u},      // run of 517 at the end
        {23, 0x8cf1fb92u},      // run of 517
        {23, 0x20a2dbc7u},      // run of 518 at the end
        {24, 0x1ce703b5u},      // run of 518
        {23, 0x1865bc20u},      // run of 519 at the end
        {24, 0xbc06b609u},      // run of 519
        {1281, 0x0a7d07e0u},    // runs 1 to 600
        {14631, 0x3a7750f6u},   // filtered view
        {100080, 0x87af95e9u},  // noise
    };
    const std::vector<Case> all = cases();
    ASSERT_EQ(expected.size(), all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        SCOPED_TRACE(all[i].name);
        const std::vector<std::uint8_t> stream = compress(all[i].data);
        EXPECT_EQ(stream.size(), expected[i].size);
        EXPECT_EQ(crc32(0, stream.data(), uInt(stream.size())), expected[i].crc);
    }
}

}  // namespace
}  // namespace encore::image
