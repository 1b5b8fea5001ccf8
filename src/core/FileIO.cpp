#include "core/FileIO.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace encore {
namespace {

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FileHandle = std::unique_ptr<std::FILE, FileCloser>;

std::string quoted(const std::filesystem::path& path) {
    return "'" + path.string() + "'";
}

}  // namespace

Result<std::vector<std::uint8_t>> readFile(const std::filesystem::path& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) {
        return makeError(ErrorCode::FileNotFound, "File " + quoted(path) + " does not exist.");
    }
    if (std::filesystem::is_directory(status)) {
        return makeError(ErrorCode::FileUnreadable,
                         "File " + quoted(path) + " is a directory, not a file.");
    }
    FileHandle file(std::fopen(path.c_str(), "rb"));
    if (!file) {
        return makeError(ErrorCode::FileUnreadable, "File " + quoted(path) + " cannot be opened (" +
                                                        std::strerror(errno) + ").");
    }
    if (std::fseek(file.get(), 0, SEEK_END) != 0) {
        return makeError(ErrorCode::FileUnreadable, "File " + quoted(path) + " is not seekable.");
    }
    const long size = std::ftell(file.get());
    if (size < 0) {
        return makeError(ErrorCode::FileUnreadable,
                         "File " + quoted(path) + " has no readable size.");
    }
    if (static_cast<std::uint64_t>(size) > kMaxFileBytes) {
        return makeError(ErrorCode::LimitExceeded, "File " + quoted(path) + " is too large (" +
                                                       std::to_string(size) + " bytes, limit " +
                                                       std::to_string(kMaxFileBytes) + ").");
    }
    std::rewind(file.get());
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (!bytes.empty() && std::fread(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
        return makeError(ErrorCode::FileUnreadable,
                         "File " + quoted(path) + " could not be read completely.");
    }
    return bytes;
}

namespace {

// Creates `path` and writes `bytes` into it; the file stays open for the caller to finish.
Result<FileHandle> createWith(const std::filesystem::path& path,
                              std::span<const std::uint8_t> bytes) {
    FileHandle file(std::fopen(path.c_str(), "wb"));
    if (!file) {
        return makeError(ErrorCode::IoError,
                         "Cannot create " + quoted(path) + " (" + std::strerror(errno) + ").");
    }
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
        return makeError(ErrorCode::IoError, "Writing " + quoted(path) + " failed.");
    }
    return file;
}

Result<void> close(FileHandle file, const std::filesystem::path& path) {
    if (std::fclose(file.release()) != 0) {
        return makeError(ErrorCode::IoError, "Closing " + quoted(path) + " failed.");
    }
    return {};
}

}  // namespace

Result<void> writeFile(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    ENCORE_TRY_ASSIGN(auto file, createWith(path, bytes));
    return close(std::move(file), path);
}

std::filesystem::path partialPath(const std::filesystem::path& path) {
    std::filesystem::path partial = path;
    partial += ".part";
    return partial;
}

namespace {

// Gives the flushed partial file of `path` its final name.
Result<void> renamePartial(const std::filesystem::path& path) {
    const std::filesystem::path partial = partialPath(path);
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) {
        return makeError(ErrorCode::IoError, "Renaming " + quoted(partial) + " to " + quoted(path) +
                                                 " failed (" + ec.message() + ").");
    }
    return {};
}

}  // namespace

Result<void> writeFileAtomically(const std::filesystem::path& path,
                                 std::span<const std::uint8_t> bytes) {
    const std::filesystem::path partial = partialPath(path);
    ENCORE_TRY_ASSIGN(auto file, createWith(partial, bytes));
    // Without the flush to the disk, a power loss after the rename could leave `path` empty:
    // file systems may commit the rename before the data.
    if (std::fflush(file.get()) != 0 || ::fdatasync(::fileno(file.get())) != 0) {
        return makeError(
            ErrorCode::IoError,
            "Flushing " + quoted(partial) + " to the disk failed (" + std::strerror(errno) + ").");
    }
    ENCORE_TRY(close(std::move(file), partial));
    return renamePartial(path);
}

Result<void> writePartialFile(const std::filesystem::path& path,
                              std::span<const std::uint8_t> bytes) {
    const std::filesystem::path partial = partialPath(path);
    ENCORE_TRY_ASSIGN(auto file, createWith(partial, bytes));
    if (std::fflush(file.get()) != 0) {
        return makeError(ErrorCode::IoError,
                         "Writing " + quoted(partial) + " failed (" + std::strerror(errno) + ").");
    }
    // Only a hint: commitFiles flushes for certain. Started now, the writeback overlaps the
    // encoding of the model's other images.
    ::sync_file_range(::fileno(file.get()), 0, 0, SYNC_FILE_RANGE_WRITE);
    return close(std::move(file), partial);
}

Result<void> commitFiles(std::span<const std::filesystem::path> paths) {
    for (const std::filesystem::path& path : paths) {
        const std::filesystem::path partial = partialPath(path);
        const int descriptor = ::open(partial.c_str(), O_RDONLY | O_CLOEXEC);
        if (descriptor < 0) {
            return makeError(ErrorCode::IoError,
                             "Cannot open " + quoted(partial) + " (" + std::strerror(errno) + ").");
        }
        const bool flushed = ::fdatasync(descriptor) == 0;
        const int flushError = errno;
        ::close(descriptor);
        if (!flushed) {
            return makeError(ErrorCode::IoError, "Flushing " + quoted(partial) +
                                                     " to the disk failed (" +
                                                     std::strerror(flushError) + ").");
        }
    }
    for (const std::filesystem::path& path : paths) {
        ENCORE_TRY(renamePartial(path));
    }
    return {};
}

}  // namespace encore
