#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

#include "encore/core/Result.h"

namespace encore {

// Copies `size` bytes from `source` to `destination`; the two must not overlap. Unlike memcpy,
// a copy of zero bytes may be handed null pointers (the data() of an empty vector or span, as
// an empty glTF buffer or a zero-length bufferView gives): it then does nothing. memcpy with a
// null pointer is undefined behaviour even for zero bytes.
inline void copyBytes(void* destination, const void* source, std::size_t size) {
    if (size != 0) {
        std::memcpy(destination, source, size);
    }
}

// Copies all of `source` to the start of `destination`, which must be at least as long (a
// shorter one is a bug: the check aborts). Either may be empty and null when `source` is empty.
inline void copyBytes(std::span<std::uint8_t> destination, std::span<const std::uint8_t> source) {
    ENCORE_CHECK(destination.size() >= source.size(),
                 "copyBytes: the destination (" + std::to_string(destination.size()) +
                     " bytes) is shorter than the source (" + std::to_string(source.size()) +
                     " bytes)");
    copyBytes(destination.data(), source.data(), source.size());
}

}  // namespace encore
