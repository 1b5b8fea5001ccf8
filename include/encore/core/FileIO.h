#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "encore/core/Result.h"

namespace encore {

// Files larger than this are refused before any allocation: no glTF asset Encore can render
// needs more, and it keeps a corrupt or hostile size from exhausting memory.
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{4} << 30;

// Reads a whole file. Errors name the path and say what went wrong (missing, a directory,
// unreadable, too large).
Result<std::vector<std::uint8_t>> readFile(const std::filesystem::path& path);

// Writes a whole file, replacing it.
Result<void> writeFile(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace encore
