#include "core/FileIO.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
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

// What a path that is not a regular file is, for messages.
std::string fileKind(const std::filesystem::file_status& status) {
    using std::filesystem::file_type;
    switch (status.type()) {
        case file_type::directory:
            return "a directory";
        case file_type::fifo:
            return "a FIFO";
        case file_type::socket:
            return "a socket";
        case file_type::character:
        case file_type::block:
            return "a device";
        default:
            return "not a regular file";
    }
}

struct DescriptorCloser {
    int descriptor = -1;
    ~DescriptorCloser() {
        if (descriptor >= 0) {
            ::close(descriptor);
        }
    }
};

}  // namespace

Result<std::vector<std::uint8_t>> readFile(const std::filesystem::path& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) {
        return makeError(ErrorCode::FileNotFound, "File " + quoted(path) + " does not exist.");
    }
    // Only regular files: opening a FIFO blocks until a writer comes, a device may never end.
    const auto notRegular = [&](const std::filesystem::file_status& found) {
        return makeError(ErrorCode::FileUnreadable, "File " + quoted(path) + " is " +
                                                        fileKind(found) + ", not a regular file.");
    };
    if (!std::filesystem::is_regular_file(status)) {
        return notRegular(status);
    }
    // Non-blocking, in case the path became a FIFO since: then open returns at once and fstat
    // says what it is.
    DescriptorCloser file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.descriptor < 0) {
        return makeError(ErrorCode::FileUnreadable, "File " + quoted(path) + " cannot be opened (" +
                                                        std::strerror(errno) + ").");
    }
    struct stat opened {};
    if (::fstat(file.descriptor, &opened) != 0 || !S_ISREG(opened.st_mode)) {
        return notRegular(std::filesystem::status(path, ec));
    }
    const auto size = static_cast<std::uint64_t>(opened.st_size);
    if (size > kMaxFileBytes) {
        return makeError(ErrorCode::LimitExceeded, "File " + quoted(path) + " is too large (" +
                                                       std::to_string(size) + " bytes, limit " +
                                                       std::to_string(kMaxFileBytes) + ").");
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t read = ::read(file.descriptor, bytes.data() + done, bytes.size() - done);
        if (read < 0 && errno == EINTR) {
            continue;
        }
        if (read <= 0) {
            return makeError(ErrorCode::FileUnreadable,
                             "File " + quoted(path) + " could not be read completely.");
        }
        done += static_cast<std::size_t>(read);
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
