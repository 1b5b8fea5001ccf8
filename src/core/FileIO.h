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

// The name writeFileAtomically gives a file while it is being written: `path` + ".part".
std::filesystem::path partialPath(const std::filesystem::path& path);

// Writes a whole file so that `path` is either absent, its previous contents, or all of `bytes`,
// whenever the process stops (a crash, SIGKILL, power loss): the bytes go to partialPath(path),
// are flushed to the disk, and that file is then renamed to `path`. A stopped write leaves at
// most the ".part" file behind.
Result<void> writeFileAtomically(const std::filesystem::path& path,
                                 std::span<const std::uint8_t> bytes);

// writeFileAtomically in two steps, for files that appear together (the images of a model):
// writePartialFile writes partialPath(path) and starts its writeback to the disk without waiting;
// commitFiles flushes each partial file to the disk (fdatasync), then renames each to its path.
// By the time a group is committed most of its data is on the disk, and the flushes wait far
// less than one flush per file did (docs/benchmarks/2026-11-24-lavapipe-batch-codecs.md).
Result<void> writePartialFile(const std::filesystem::path& path,
                              std::span<const std::uint8_t> bytes);
Result<void> commitFiles(std::span<const std::filesystem::path> paths);

}  // namespace encore
