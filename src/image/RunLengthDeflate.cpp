// A zlib stream of one dynamic-Huffman deflate block whose only matches are runs (distance 1):
// no LZ77 search, so it costs a scan that splits the data into literals and runs and counts
// their symbols, and a pass that writes their codes, reading only the literals again. On
// filtered rendered views (long runs of transparent black, small residuals on the object) that
// is what most of libdeflate's time went to find anyway.

#include "image/RunLengthDeflate.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace encore::image {
namespace {

constexpr int kEndOfBlock = 256;
constexpr int kLiteralLengthSymbols = 286;  // Codes 286 and 287 never occur.
constexpr int kMinRun = 3;
constexpr int kMaxRun = 258;

// Deflate's length codes: for each run length 3..258 its symbol, extra bit count and extra value.
struct LengthCode {
    std::uint16_t symbol;
    std::uint8_t extraBits;
    std::uint16_t extraValue;
};

constexpr std::array<LengthCode, kMaxRun + 1> makeLengthCodes() {
    constexpr std::uint16_t kBase[29] = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                         15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                         67, 83, 99, 115, 131, 163, 195, 227, 258};
    constexpr std::uint8_t kExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                         2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    std::array<LengthCode, kMaxRun + 1> codes{};
    for (int code = 0; code < 29; ++code) {
        const int last = code == 28 ? 258 : kBase[code + 1] - 1;
        for (int length = kBase[code]; length <= last; ++length) {
            codes[length] = {std::uint16_t(257 + code), kExtra[code],
                             std::uint16_t(length - kBase[code])};
        }
    }
    return codes;
}

constexpr std::array<LengthCode, kMaxRun + 1> kLengthCodes = makeLengthCodes();

// The first position from `at` (at least 1) on where a run starts: whose byte and the two
// after it repeat the byte before it. Eight positions a step: a position starts a run where the
// data XOR itself shifted by one byte is zero there and at the next two positions. Repeats
// shorter than kMinRun stay literals without a branch of their own.
std::size_t nextRun(const std::uint8_t* data, std::size_t at, std::size_t size) {
    constexpr std::uint64_t kOnes = 0x0101010101010101ull;
    for (; at + 10 <= size; at += 8) {
        // Words in variables, not an array: GCC kept an array on the stack (10% slower).
        const auto load = [&](std::size_t offset) {
            std::uint64_t word;
            std::memcpy(&word, data + at - 1 + offset, 8);
            return word;
        };
        const std::uint64_t before = load(0);
        const std::uint64_t first = load(1);
        const std::uint64_t second = load(2);
        const std::uint64_t third = load(3);
        const std::uint64_t differ = (before ^ first) | (first ^ second) | (second ^ third);
        // The lowest flagged byte is the first zero one (a borrow only runs upwards).
        const std::uint64_t zeros = (differ - kOnes) & ~differ & (kOnes << 7);
        if (zeros != 0) {
            return at + std::size_t(__builtin_ctzll(zeros) / 8);
        }
    }
    for (; at + 3 <= size; ++at) {
        const std::uint8_t value = data[at - 1];
        if (data[at] == value && data[at + 1] == value && data[at + 2] == value) {
            return at;
        }
    }
    return size;
}

// How many bytes from `at` on repeat the byte before it (no limit: runs are split later).
std::size_t repeatLength(const std::uint8_t* data, std::size_t at, std::size_t size) {
    const std::uint8_t value = data[at - 1];
    const std::uint64_t pattern = 0x0101010101010101ull * value;
    std::size_t length = 0;
    // Long runs (a view's background) 32 bytes a step.
    const auto load = [&](std::size_t offset) {
        std::uint64_t word;
        std::memcpy(&word, data + at + length + offset, 8);
        return word ^ pattern;
    };
    while (at + length + 32 <= size) {
        if ((load(0) | load(8) | load(16) | load(24)) != 0) {
            break;
        }
        length += 32;
    }
    while (at + length + 8 <= size) {
        std::uint64_t word;
        std::memcpy(&word, data + at + length, 8);
        const std::uint64_t differ = word ^ pattern;
        if (differ != 0) {
            return length + std::size_t(__builtin_ctzll(differ) / 8);
        }
        length += 8;
    }
    while (at + length < size && data[at + length] == value) {
        ++length;
    }
    return length;
}

// The symbols of the data in order as stretches: `literals` bytes coded one by one (read again
// from the data), then a run of `run` bytes (kMinRun..kMaxRun; 0: none) repeating the byte before.
struct Stretch {
    std::uint32_t literals;
    std::uint32_t run;
};

// The stretches of one image, kept by the thread for the next (a 1 MiB view has a few
// thousand; more than kKeptStretches, from a one-off large image, are freed after use), and the
// frequency of each literal/length symbol.
constexpr std::size_t kKeptStretches = std::size_t(1) << 20;
struct Tokens {
    std::vector<Stretch> stretches;
    std::vector<std::uint32_t> frequencies;
};

// Splits `data` into stretches, as deflate's greedy matcher with only distance 1 would, and
// counts each literal/length symbol: the first byte of a repeated byte's span is a literal, the
// rest runs of at most kMaxRun, and what is left under kMinRun literals again.
void tokenize(const std::uint8_t* data, std::size_t size, Tokens& tokens) {
    tokens.stretches.clear();
    tokens.frequencies.assign(kLiteralLengthSymbols, 0);
    std::uint32_t* frequencies = tokens.frequencies.data();
    // Literals counted in four tables: a repeated byte's increments do not wait on each other.
    std::uint32_t literalCounts[4][256] = {};
    std::size_t literalStart = 0;  // The first byte not yet in a stretch.
    auto closeLiterals = [&](std::size_t end, std::uint32_t run) {
        std::size_t i = literalStart;
        for (; i + 4 <= end; i += 4) {
            ++literalCounts[0][data[i]];
            ++literalCounts[1][data[i + 1]];
            ++literalCounts[2][data[i + 2]];
            ++literalCounts[3][data[i + 3]];
        }
        for (; i < end; ++i) {
            ++literalCounts[0][data[i]];
        }
        std::size_t literals = end - literalStart;
        for (; literals > UINT32_MAX; literals -= UINT32_MAX) {
            tokens.stretches.push_back({UINT32_MAX, 0});
        }
        tokens.stretches.push_back({std::uint32_t(literals), run});
        literalStart = end;
    };
    std::size_t at = 1;
    while (at < size) {
        at = nextRun(data, at, size);
        if (at >= size) {
            break;
        }
        std::size_t left = repeatLength(data, at, size);
        while (left >= kMinRun) {
            const std::size_t run = std::min(left, std::size_t(kMaxRun));
            closeLiterals(at, std::uint32_t(run));
            ++frequencies[kLengthCodes[run].symbol];
            at += run;
            literalStart = at;
            left -= run;
        }
        at += left;  // Too short for a run: literals.
    }
    if (literalStart < size) {
        closeLiterals(size, 0);
    }
    for (int byte = 0; byte < 256; ++byte) {
        frequencies[byte] = literalCounts[0][byte] + literalCounts[1][byte] +
                            literalCounts[2][byte] + literalCounts[3][byte];
    }
}

// Code lengths of at most `maxLength` bits for `frequencies` (zero-frequency symbols get 0):
// Huffman's lengths, then, where they exceed the limit, the overflow moved to the limit and the
// Kraft sum repaired by lengthening the deepest shorter codes (as miniz does); the most
// frequent symbols keep the shortest codes.
std::vector<std::uint8_t> codeLengths(const std::vector<std::uint32_t>& frequencies,
                                      int maxLength) {
    const std::size_t count = frequencies.size();
    std::vector<std::uint8_t> lengths(count, 0);
    std::vector<std::uint32_t> symbols;
    for (std::uint32_t s = 0; s < count; ++s) {
        if (frequencies[s] > 0) {
            symbols.push_back(s);
        }
    }
    if (symbols.empty()) {
        return lengths;
    }
    if (symbols.size() == 1) {
        lengths[symbols[0]] = 1;
        return lengths;
    }
    std::sort(symbols.begin(), symbols.end(), [&](std::uint32_t a, std::uint32_t b) {
        return frequencies[a] != frequencies[b] ? frequencies[a] < frequencies[b] : a < b;
    });
    // Two-queue Huffman: leaves in frequency order, internal nodes in creation order.
    const std::size_t leaves = symbols.size();
    std::vector<std::uint64_t> weight(2 * leaves - 1);
    std::vector<std::uint32_t> parent(2 * leaves - 1, 0);
    for (std::size_t i = 0; i < leaves; ++i) {
        weight[i] = frequencies[symbols[i]];
    }
    std::size_t nextLeaf = 0;
    std::size_t nextNode = leaves;
    std::size_t created = leaves;
    auto takeSmallest = [&]() {
        if (nextLeaf < leaves && (nextNode >= created || weight[nextLeaf] <= weight[nextNode])) {
            return nextLeaf++;
        }
        return nextNode++;
    };
    while (created < 2 * leaves - 1) {
        const std::size_t a = takeSmallest();
        const std::size_t b = takeSmallest();
        weight[created] = weight[a] + weight[b];
        parent[a] = parent[b] = std::uint32_t(created);
        ++created;
    }
    std::vector<int> depth(2 * leaves - 1, 0);
    for (std::size_t node = 2 * leaves - 2; node-- > 0;) {
        depth[node] = depth[parent[node]] + 1;
    }
    // Codes per length, limited and repaired.
    std::vector<std::uint32_t> perLength(64, 0);
    for (std::size_t i = 0; i < leaves; ++i) {
        ++perLength[std::min(depth[i], maxLength)];
    }
    std::uint64_t kraft = 0;
    for (int length = 1; length <= maxLength; ++length) {
        kraft += std::uint64_t(perLength[length]) << (maxLength - length);
    }
    while (kraft > (std::uint64_t(1) << maxLength)) {
        --perLength[maxLength];
        for (int length = maxLength - 1; length > 0; --length) {
            if (perLength[length] > 0) {
                --perLength[length];
                perLength[length + 1] += 2;
                break;
            }
        }
        --kraft;
    }
    // Shortest lengths to the most frequent symbols (the end of `symbols`).
    std::size_t next = leaves;
    for (int length = 1; length <= maxLength; ++length) {
        for (std::uint32_t n = 0; n < perLength[length]; ++n) {
            lengths[symbols[--next]] = std::uint8_t(length);
        }
    }
    return lengths;
}

// Canonical codes for `lengths`, bit-reversed for deflate's least-significant-bit-first order.
std::vector<std::uint16_t> canonicalCodes(const std::vector<std::uint8_t>& lengths) {
    std::array<std::uint16_t, 17> perLength{};
    for (std::uint8_t length : lengths) {
        ++perLength[length];
    }
    perLength[0] = 0;
    std::array<std::uint16_t, 17> next{};
    std::uint16_t code = 0;
    for (int length = 1; length <= 16; ++length) {
        code = std::uint16_t((code + perLength[length - 1]) << 1);
        next[length] = code;
    }
    std::vector<std::uint16_t> codes(lengths.size(), 0);
    for (std::size_t s = 0; s < lengths.size(); ++s) {
        const int length = lengths[s];
        if (length == 0) {
            continue;
        }
        std::uint16_t value = next[length]++;
        std::uint16_t reversed = 0;
        for (int bit = 0; bit < length; ++bit) {
            reversed = std::uint16_t((reversed << 1) | ((value >> bit) & 1));
        }
        codes[s] = reversed;
    }
    return codes;
}

// Writes into a buffer sized beforehand for the worst case (RunLengthDeflate's bound), eight
// bytes at a time: each flush stores the whole bit buffer and moves on by its complete bytes,
// which the bound's slack (over 500 bytes past any stream's end) leaves room for.
class BitWriter {
  public:
    explicit BitWriter(std::uint8_t* out) : mOut(out) {}

    // At most 64 bits in all since the last flush (which leaves up to 7).
    void add(std::uint32_t value, int bits) {
        mBits |= std::uint64_t(value) << mCount;
        mCount += bits;
    }
    // A symbol from a code table: its bits under 1 << 24, their count above.
    void add(std::uint32_t entry) { add(entry & 0xffffff, int(entry >> 24)); }

    void flush() {
        std::memcpy(mOut, &mBits, 8);  // Little-endian: deflate's bit order.
        mOut += mCount >> 3;
        mBits >>= mCount & ~7;
        mCount &= 7;
    }

    void put(std::uint32_t value, int bits) {
        add(value, bits);
        flush();
    }

    // Writes the last partial byte; returns the end of the data.
    std::uint8_t* finish() {
        flush();
        if (mCount > 0) {
            *mOut++ = std::uint8_t(mBits);
        }
        return mOut;
    }

  private:
    std::uint8_t* mOut;
    std::uint64_t mBits = 0;
    int mCount = 0;
};

// The code length sequence (literal/length lengths then distance lengths) in deflate's
// run-length alphabet: 0..15 literally, 16 = repeat the previous 3..6 times, 17 = 3..10 zeros,
// 18 = 11..138 zeros. Each entry is symbol | extra value << 8.
std::vector<std::uint16_t> codeLengthSymbols(const std::vector<std::uint8_t>& all) {
    std::vector<std::uint16_t> out;
    std::size_t i = 0;
    while (i < all.size()) {
        const std::uint8_t value = all[i];
        std::size_t run = 1;
        while (i + run < all.size() && all[i + run] == value) {
            ++run;
        }
        std::size_t left = run;
        if (value == 0) {
            while (left >= 11) {
                const std::size_t n = std::min<std::size_t>(left, 138);
                out.push_back(std::uint16_t(18 | (n - 11) << 8));
                left -= n;
            }
            if (left >= 3) {
                out.push_back(std::uint16_t(17 | (left - 3) << 8));
                left = 0;
            }
        } else {
            out.push_back(value);
            --left;
            while (left >= 3) {
                const std::size_t n = std::min<std::size_t>(left, 6);
                out.push_back(std::uint16_t(16 | (n - 3) << 8));
                left -= n;
            }
        }
        for (; left > 0; --left) {
            out.push_back(value);
        }
        i += run;
    }
    return out;
}

}  // namespace

std::size_t runLengthZlibBound(std::size_t size) {
    // At most 15 bits per byte of data (a literal each); the header takes under 1 KiB.
    return 2 + size * 2 + 1024 + 4;
}

std::size_t runLengthZlib(std::span<const std::uint8_t> data, std::uint8_t* out) {
    thread_local Tokens tokens;
    tokenize(data.data(), data.size(), tokens);
    std::vector<std::uint32_t>& frequencies = tokens.frequencies;
    frequencies[kEndOfBlock] = 1;
    const std::vector<std::uint8_t> literalLengths = codeLengths(frequencies, 15);
    const std::vector<std::uint16_t> literalCodes = canonicalCodes(literalLengths);
    std::size_t literalCount = kLiteralLengthSymbols;
    while (literalCount > 257 && literalLengths[literalCount - 1] == 0) {
        --literalCount;
    }
    // One distance code, 0 (distance 1), one bit long, as deflate allows for a single code.
    std::vector<std::uint8_t> all(literalLengths.begin(),
                                  literalLengths.begin() + std::ptrdiff_t(literalCount));
    all.push_back(1);
    const std::vector<std::uint16_t> lengthSymbols = codeLengthSymbols(all);
    std::vector<std::uint32_t> lengthFrequencies(19, 0);
    for (std::uint16_t symbol : lengthSymbols) {
        ++lengthFrequencies[symbol & 0xff];
    }
    // zlib refuses an incomplete code-length code: give a lone symbol a partner.
    if (std::count_if(lengthFrequencies.begin(), lengthFrequencies.end(),
                      [](std::uint32_t f) { return f > 0; }) < 2) {
        ++lengthFrequencies[lengthFrequencies[0] > 0 ? 1 : 0];
    }
    const std::vector<std::uint8_t> lengthLengths = codeLengths(lengthFrequencies, 7);
    const std::vector<std::uint16_t> lengthCodes = canonicalCodes(lengthLengths);
    static constexpr std::uint8_t kOrder[19] = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                11, 4,  12, 3, 13, 2, 14, 1, 15};
    int orderCount = 19;
    while (orderCount > 4 && lengthLengths[kOrder[orderCount - 1]] == 0) {
        --orderCount;
    }

    out[0] = 0x78;  // Deflate, 32 KiB window.
    out[1] = 0x01;  // Fastest compression; (0x7801 % 31) == 0.
    BitWriter writer(out + 2);
    writer.put(1, 1);  // The final block,
    writer.put(2, 2);  // with dynamic Huffman codes.
    writer.put(std::uint32_t(literalCount - 257), 5);
    writer.put(0, 5);  // One distance code.
    writer.put(std::uint32_t(orderCount - 4), 4);
    for (int i = 0; i < orderCount; ++i) {
        writer.put(lengthLengths[kOrder[i]], 3);
    }
    static constexpr int kExtraBits[19] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3, 7};
    for (std::uint16_t entry : lengthSymbols) {
        const int symbol = entry & 0xff;
        writer.put(lengthCodes[symbol], lengthLengths[symbol]);
        if (kExtraBits[symbol] > 0) {
            writer.put(entry >> 8, kExtraBits[symbol]);
        }
    }
    // Each symbol's code and bit count in one word; a run's length code, extra bits and the
    // distance code (the single one-bit code 0) together.
    std::array<std::uint32_t, 256> literalEntries;
    for (int byte = 0; byte < 256; ++byte) {
        literalEntries[byte] = std::uint32_t(literalLengths[byte]) << 24 | literalCodes[byte];
    }
    std::array<std::uint32_t, kMaxRun + 1> runEntries{};
    for (int length = kMinRun; length <= kMaxRun; ++length) {
        const LengthCode& code = kLengthCodes[length];
        const int codeBits = literalLengths[code.symbol];
        const int bits = codeBits + code.extraBits + 1;
        runEntries[length] = std::uint32_t(bits) << 24 |
                             std::uint32_t(code.extraValue) << codeBits | literalCodes[code.symbol];
    }
    const std::uint8_t* next = data.data();
    for (const Stretch& stretch : tokens.stretches) {
        const std::uint8_t* end = next + stretch.literals;
        // At most 7 bits wait in the writer: three 15-bit codes fit before a flush, and after
        // the last three, two more and a run's 21 bits.
        for (; end - next >= 3; next += 3) {
            writer.add(literalEntries[next[0]]);
            writer.add(literalEntries[next[1]]);
            writer.add(literalEntries[next[2]]);
            writer.flush();
        }
        for (; next < end; ++next) {
            writer.add(literalEntries[*next]);
        }
        writer.add(runEntries[stretch.run]);  // Nothing for 0.
        writer.flush();
        next += stretch.run;
    }
    writer.put(literalCodes[kEndOfBlock], literalLengths[kEndOfBlock]);
    std::uint8_t* end = writer.finish();
    if (tokens.stretches.capacity() > kKeptStretches) {
        tokens.stretches = {};
    }
    const std::uint32_t adler = libdeflate_adler32(1, data.data(), data.size());
    for (int shift = 24; shift >= 0; shift -= 8) {
        *end++ = std::uint8_t(adler >> shift);
    }
    return std::size_t(end - out);
}

}  // namespace encore::image
