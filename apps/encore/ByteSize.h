#pragma once

// Sizes in bytes as options take them (encore batch --shard-size).

#include <cstdint>
#include <string>

#include "encore/core/Result.h"

namespace encore::app {

// "1GiB", "500MB", "64k", "1000000": a number of bytes with an optional unit (k, M, G, T in
// powers of 1000, Ki, Mi, Gi, Ti in powers of 1024, a trailing B optional, any letter case).
// InvalidArgument, naming `option`, for anything else or less than a byte.
Result<std::uint64_t> parseByteSize(const std::string& text, const std::string& option);

}  // namespace encore::app
