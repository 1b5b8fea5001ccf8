// SHA-256 against the test vectors of FIPS 180-4's examples (NIST CSRC "Cryptographic Standards
// and Guidelines: Examples with Intermediate Values") and incremental hashing against one call.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/Sha256.h"

namespace encore {
namespace {

std::span<const std::uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::string digest(Sha256::Kernel kernel, std::span<const std::uint8_t> bytes) {
    Sha256 hash(kernel);
    hash.update(bytes);
    return Sha256::toHex(hash.finish());
}

// Every kernel this processor runs: the portable one, and the SHA extensions where present.
std::vector<Sha256::Kernel> kernels() {
    std::vector<Sha256::Kernel> kernels = {Sha256::Kernel::Portable};
    if (Sha256::cpuHasShaExtensions()) {
        kernels.push_back(Sha256::Kernel::ShaExtensions);
    }
    return kernels;
}

TEST(Sha256Test, StandardTestVectors) {
    const std::string million(1000000, 'a');
    for (const Sha256::Kernel kernel : kernels()) {
        SCOPED_TRACE(kernel == Sha256::Kernel::Portable ? "portable" : "SHA extensions");
        EXPECT_EQ(digest(kernel, bytesOf("")),
                  "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
        EXPECT_EQ(digest(kernel, bytesOf("abc")),
                  "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
        // 56 bytes: the padding needs a second block.
        EXPECT_EQ(
            digest(kernel, bytesOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
        EXPECT_EQ(
            digest(kernel, bytesOf("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmn"
                                   "hijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu")),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
        EXPECT_EQ(digest(kernel, bytesOf(million)),
                  "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    }
    EXPECT_EQ(Sha256::hex(bytesOf("abc")), digest(Sha256::Kernel::Portable, bytesOf("abc")));
}

TEST(Sha256Test, PiecesHashLikeTheWhole) {
    std::vector<std::uint8_t> message(1000);
    for (std::size_t i = 0; i < message.size(); ++i) {
        message[i] = std::uint8_t(i * 7 + i / 13);
    }
    const std::string whole = Sha256::hex(message);
    // Pieces that straddle block boundaries in every way, and empty ones.
    for (const std::size_t piece : {1u, 3u, 63u, 64u, 65u, 200u, 999u}) {
        Sha256 hash(Sha256::Kernel::Portable);
        hash.update({});
        for (std::size_t offset = 0; offset < message.size(); offset += piece) {
            hash.update(
                std::span(message).subspan(offset, std::min(piece, message.size() - offset)));
        }
        EXPECT_EQ(Sha256::toHex(hash.finish()), whole) << "pieces of " << piece;
        // finish() starts a new message.
        EXPECT_EQ(Sha256::toHex(hash.finish()), Sha256::hex({}));
    }
    // Every length around a block: the padding's two cases.
    for (std::size_t length = 50; length < 130; ++length) {
        Sha256 hash;
        hash.update(std::span(message).first(length / 2));
        hash.update(std::span(message).subspan(length / 2, length - length / 2));
        EXPECT_EQ(Sha256::toHex(hash.finish()), Sha256::hex(std::span(message).first(length)))
            << length;
    }
}

}  // namespace
}  // namespace encore
