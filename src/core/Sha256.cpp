#include "core/Sha256.h"

#include <algorithm>
#include <bit>
#include <cstring>

#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

namespace encore {
namespace {

constexpr std::array<std::uint32_t, 64> kRoundConstants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

constexpr std::array<std::uint32_t, 8> kInitialState = {
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

std::uint32_t loadBigEndian(const std::uint8_t* bytes) {
    return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 |
           std::uint32_t(bytes[2]) << 8 | std::uint32_t(bytes[3]);
}

void compressPortable(std::array<std::uint32_t, 8>& state,
                      const std::uint8_t* blocks,
                      std::size_t count) {
    for (; count > 0; --count, blocks += 64) {
        std::array<std::uint32_t, 64> schedule;
        for (int i = 0; i < 16; ++i) {
            schedule[i] = loadBigEndian(blocks + 4 * i);
        }
        for (int i = 16; i < 64; ++i) {
            const std::uint32_t w15 = schedule[i - 15];
            const std::uint32_t w2 = schedule[i - 2];
            const std::uint32_t s0 = std::rotr(w15, 7) ^ std::rotr(w15, 18) ^ (w15 >> 3);
            const std::uint32_t s1 = std::rotr(w2, 17) ^ std::rotr(w2, 19) ^ (w2 >> 10);
            schedule[i] = schedule[i - 16] + s0 + schedule[i - 7] + s1;
        }
        auto [a, b, c, d, e, f, g, h] = state;
        for (int i = 0; i < 64; ++i) {
            const std::uint32_t sum1 = std::rotr(e, 6) ^ std::rotr(e, 11) ^ std::rotr(e, 25);
            const std::uint32_t choice = (e & f) ^ (~e & g);
            const std::uint32_t t1 = h + sum1 + choice + kRoundConstants[i] + schedule[i];
            const std::uint32_t sum0 = std::rotr(a, 2) ^ std::rotr(a, 13) ^ std::rotr(a, 22);
            const std::uint32_t majority = (a & b) ^ (a & c) ^ (b & c);
            h = g;
            g = f;
            f = e;
            e = d + t1;
            d = c;
            c = b;
            b = a;
            a = t1 + sum0 + majority;
        }
        const std::array<std::uint32_t, 8> added = {a, b, c, d, e, f, g, h};
        for (std::size_t i = 0; i < 8; ++i) {
            state[i] += added[i];
        }
    }
}

#if defined(__x86_64__)

// The SHA extensions hold the state as two registers, ABEF and CDGH, and do two rounds per
// instruction (sha256rnds2); sha256msg1 and sha256msg2 extend the message schedule four words
// at a time. The layout follows Intel's "Intel SHA Extensions" white paper (2013).
__attribute__((target("sha,sse4.1,ssse3"))) void compressShaExtensions(
    std::array<std::uint32_t, 8>& state,
    const std::uint8_t* blocks,
    std::size_t count) {
    // Each 32-bit word of the message is big-endian.
    const __m128i byteSwap = _mm_set_epi64x(0x0c0d0e0f08090a0bULL, 0x0405060700010203ULL);
    __m128i cdab = _mm_shuffle_epi32(_mm_loadu_si128(reinterpret_cast<__m128i*>(&state[0])), 0xB1);
    __m128i efgh = _mm_shuffle_epi32(_mm_loadu_si128(reinterpret_cast<__m128i*>(&state[4])), 0x1B);
    __m128i abef = _mm_alignr_epi8(cdab, efgh, 8);
    __m128i cdgh = _mm_blend_epi16(efgh, cdab, 0xF0);
    for (; count > 0; --count, blocks += 64) {
        const __m128i abefBefore = abef;
        const __m128i cdghBefore = cdgh;
        __m128i words[4];  // The schedule's words 4g .. 4g + 3 of group g in words[g % 4].
        for (int group = 0; group < 16; ++group) {
            __m128i& current = words[group % 4];
            if (group < 4) {
                current = _mm_shuffle_epi8(
                    _mm_loadu_si128(reinterpret_cast<const __m128i*>(blocks + 16 * group)),
                    byteSwap);
            }
            __m128i message = _mm_add_epi32(
                current,
                _mm_loadu_si128(reinterpret_cast<const __m128i*>(&kRoundConstants[4 * group])));
            cdgh = _mm_sha256rnds2_epu32(cdgh, abef, message);
            if (group >= 3 && group <= 14) {
                // Words of group + 1, their sigma-0 part added by sha256msg1 three groups ago.
                __m128i& next = words[(group + 1) % 4];
                next = _mm_add_epi32(next, _mm_alignr_epi8(current, words[(group + 3) % 4], 4));
                next = _mm_sha256msg2_epu32(next, current);
            }
            message = _mm_shuffle_epi32(message, 0x0E);
            abef = _mm_sha256rnds2_epu32(abef, cdgh, message);
            if (group >= 1 && group <= 12) {
                __m128i& previous = words[(group + 3) % 4];
                previous = _mm_sha256msg1_epu32(previous, current);
            }
        }
        abef = _mm_add_epi32(abef, abefBefore);
        cdgh = _mm_add_epi32(cdgh, cdghBefore);
    }
    const __m128i feba = _mm_shuffle_epi32(abef, 0x1B);
    const __m128i dchg = _mm_shuffle_epi32(cdgh, 0xB1);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[0]), _mm_blend_epi16(feba, dchg, 0xF0));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&state[4]), _mm_alignr_epi8(dchg, feba, 8));
}

#endif

}  // namespace

bool Sha256::cpuHasShaExtensions() {
#if defined(__x86_64__)
    // CPUID rather than __builtin_cpu_supports("sha"), which clang 14 (the fuzz build) lacks:
    // leaf 7 EBX bit 29 is SHA, leaf 1 ECX bits 19 and 9 are SSE4.1 and SSSE3.
    static const bool has = [] {
        unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
        if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) {
            return false;
        }
        const bool sse = (ecx & (1u << 19)) && (ecx & (1u << 9));
        if (!__get_cpuid_count(7, 0, &eax, &ebx, &ecx, &edx)) {
            return false;
        }
        return sse && (ebx & (1u << 29)) != 0;
    }();
    return has;
#else
    return false;
#endif
}

Sha256::Sha256() : Sha256(cpuHasShaExtensions() ? Kernel::ShaExtensions : Kernel::Portable) {}

Sha256::Sha256(Kernel kernel)
    : mKernel(kernel == Kernel::ShaExtensions && cpuHasShaExtensions() ? kernel
                                                                       : Kernel::Portable) {
    reset();
}

void Sha256::reset() {
    mState = kInitialState;
    mBlockSize = 0;
    mMessageBytes = 0;
}

void Sha256::compress(const std::uint8_t* blocks, std::size_t count) {
#if defined(__x86_64__)
    if (mKernel == Kernel::ShaExtensions) {
        compressShaExtensions(mState, blocks, count);
        return;
    }
#endif
    compressPortable(mState, blocks, count);
}

void Sha256::update(std::span<const std::uint8_t> bytes) {
    mMessageBytes += bytes.size();
    std::size_t offset = 0;
    if (mBlockSize > 0) {
        const std::size_t take = std::min(bytes.size(), mBlock.size() - mBlockSize);
        std::memcpy(mBlock.data() + mBlockSize, bytes.data(), take);
        mBlockSize += take;
        offset = take;
        if (mBlockSize < mBlock.size()) {
            return;
        }
        compress(mBlock.data(), 1);
        mBlockSize = 0;
    }
    // Whole blocks straight from the input, without copying them.
    const std::size_t blocks = (bytes.size() - offset) / mBlock.size();
    if (blocks > 0) {
        compress(bytes.data() + offset, blocks);
        offset += blocks * mBlock.size();
    }
    if (offset < bytes.size()) {
        mBlockSize = bytes.size() - offset;
        std::memcpy(mBlock.data(), bytes.data() + offset, mBlockSize);
    }
}

Sha256::Digest Sha256::finish() {
    const std::uint64_t messageBits = mMessageBytes * 8;
    // A 1 bit, zeros up to 56 bytes modulo 64, then the length in bits, big-endian.
    std::array<std::uint8_t, 72> padding{};
    padding[0] = 0x80;
    const std::size_t zeros = (mBlockSize < 56 ? 56 : 120) - mBlockSize;
    for (int i = 0; i < 8; ++i) {
        padding[zeros + i] = std::uint8_t(messageBits >> (56 - 8 * i));
    }
    update(std::span(padding.data(), zeros + 8));
    Digest digest;
    for (std::size_t i = 0; i < 8; ++i) {
        for (std::size_t byte = 0; byte < 4; ++byte) {
            digest[4 * i + byte] = std::uint8_t(mState[i] >> (24 - 8 * byte));
        }
    }
    reset();
    return digest;
}

std::string Sha256::toHex(const Digest& digest) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string text;
    text.reserve(2 * digest.size());
    for (const std::uint8_t byte : digest) {
        text += kDigits[byte >> 4];
        text += kDigits[byte & 15];
    }
    return text;
}

std::string Sha256::hex(std::span<const std::uint8_t> bytes) {
    Sha256 hash;
    hash.update(bytes);
    return toHex(hash.finish());
}

}  // namespace encore
