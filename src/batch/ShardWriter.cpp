#include "batch/ShardWriter.h"

#include <archive.h>
#include <archive_entry.h>

#include <algorithm>
#include <cstdio>

#include "batch/ModelOutput.h"
#include "core/FileIO.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

constexpr const char* kShardPrefix = "shard-";
constexpr const char* kShardExtension = ".tar";
constexpr std::uint64_t kTarBlock = 512;

// "shard-000012.tar" -> 12; -1 for any other name.
long shardIndex(const std::string& fileName) {
    const std::string prefix = kShardPrefix;
    const std::string extension = kShardExtension;
    if (!fileName.starts_with(prefix) || !fileName.ends_with(extension) ||
        fileName.size() != prefix.size() + 6 + extension.size()) {
        return -1;
    }
    const std::string digits = fileName.substr(prefix.size(), 6);
    if (digits.find_first_not_of("0123456789") != std::string::npos) {
        return -1;
    }
    return std::stol(digits);
}

// The key of a member name: its folder and its file name up to the first dot.
std::string memberKey(const std::string& member) {
    const std::size_t slash = member.rfind('/');
    const std::size_t start = slash == std::string::npos ? 0 : slash + 1;
    const std::size_t dot = member.find('.', start);
    return member.substr(0, dot);
}

Error archiveError(archive* archive, const std::string& what) {
    const char* message = archive_error_string(archive);
    return makeError(ErrorCode::IoError,
                     what + " (" + (message ? message : "libarchive gave no reason") + ").");
}

// A sample's files, images first in name order, metadata.json then transforms.json last.
std::vector<fs::path> sampleFiles(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        if (it->is_regular_file(ec) && it->path().extension() != ".part") {
            files.push_back(it->path());
        }
    }
    const auto rank = [](const fs::path& path) {
        const std::string name = path.filename().string();
        return name == kTransformsFileName ? 2 : name == "metadata.json" ? 1 : 0;
    };
    std::sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) {
        return std::pair(rank(a), a.filename()) < std::pair(rank(b), b.filename());
    });
    return files;
}

// Removes the files of a sample's folder, not the folders: another sample may lie in a folder
// below it ("a" and "a/b"), and the device thread may be creating one beside it at any moment.
// pruneEmptyFolders removes the folders once nothing is being written.
void removeSampleFiles(const fs::path& folder) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        if (it->is_regular_file(ec)) {
            files.push_back(it->path());
        }
    }
    for (const fs::path& file : files) {
        fs::remove(file, ec);
    }
}

// Removes the empty folders under `root`, deepest first, and `root` if it is left empty.
void pruneEmptyFolders(const fs::path& root) {
    std::error_code ec;
    std::vector<fs::path> folders;
    for (auto it = fs::recursive_directory_iterator(root, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_directory(ec)) {
            folders.push_back(it->path());
        }
    }
    std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
        return a.native().size() > b.native().size();
    });
    folders.push_back(root);
    for (const fs::path& folder : folders) {
        fs::remove(folder, ec);  // Fails, leaving it, unless it is empty.
    }
}

}  // namespace

std::string shardKey(const std::string& sampleName) {
    std::string key = sampleName;
    std::replace(key.begin(), key.end(), '.', '_');
    return key;
}

Result<std::vector<std::string>> tarMemberNames(const fs::path& tar) {
    archive* reader = archive_read_new();
    archive_read_support_format_tar(reader);
    std::vector<std::string> names;
    Result<std::vector<std::string>> result = names;
    if (archive_read_open_filename(reader, tar.c_str(), 1 << 16) != ARCHIVE_OK) {
        result = archiveError(reader, "Cannot open the shard '" + tar.string() + "'");
    } else {
        archive_entry* entry = nullptr;
        int status = ARCHIVE_OK;
        while ((status = archive_read_next_header(reader, &entry)) == ARCHIVE_OK) {
            names.push_back(archive_entry_pathname(entry));
            archive_read_data_skip(reader);
        }
        result = status == ARCHIVE_EOF
                     ? Result<std::vector<std::string>>(std::move(names))
                     : Result<std::vector<std::string>>(
                           archiveError(reader, "Cannot read the shard '" + tar.string() + "'"));
    }
    archive_read_free(reader);
    return result;
}

Result<std::unique_ptr<ShardWriter>> ShardWriter::open(const fs::path& output,
                                                       std::uint64_t samplesPerShard,
                                                       std::uint64_t bytesPerShard) {
    std::unique_ptr<ShardWriter> writer(new ShardWriter());
    writer->mOutput = output;
    writer->mStaging = output / kStagingFolderName;
    writer->mSamplesPerShard = samplesPerShard;
    writer->mBytesPerShard = bytesPerShard;
    std::error_code ec;
    fs::create_directories(writer->mStaging, ec);
    if (ec) {
        return makeError(
            ErrorCode::IoError,
            "Cannot create the folder '" + writer->mStaging.string() + "' (" + ec.message() + ").");
    }
    std::vector<fs::path> partial;
    long last = -1;
    for (auto it = fs::directory_iterator(output, ec); !ec && it != fs::directory_iterator();
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.starts_with(kShardPrefix) && name.ends_with(".tar.part")) {
            partial.push_back(it->path());  // A killed run's: its samples are still staged.
        }
        const long index = shardIndex(name);
        if (index < 0) {
            continue;
        }
        last = std::max(last, index);
        ENCORE_TRY_ASSIGN(auto members, tarMemberNames(it->path()));
        for (const std::string& member : members) {
            writer->mFinishedKeys.insert(memberKey(member));
        }
    }
    for (const fs::path& path : partial) {
        fs::remove(path, ec);
    }
    writer->mNextIndex = std::size_t(last + 1);
    return writer;
}

ShardWriter::~ShardWriter() {
    if (mArchive) {
        // Not closed (the batch failed): the partial shard stays partial, as a kill leaves it.
        archive_write_free(mArchive);
    }
}

bool ShardWriter::finished(const std::string& sampleName) const {
    return mFinishedKeys.contains(shardKey(sampleName));
}

Result<void> ShardWriter::startShard() {
    char name[32];
    std::snprintf(name, sizeof(name), "%s%06zu%s", kShardPrefix, mNextIndex, kShardExtension);
    mCurrentPath = mOutput / name;
    mArchive = archive_write_new();
    // ustar, with pax headers only for names longer than ustar's 100 bytes.
    archive_write_set_format_pax_restricted(mArchive);
    if (archive_write_open_filename(mArchive, partialPath(mCurrentPath).c_str()) != ARCHIVE_OK) {
        Error error = archiveError(
            mArchive, "Cannot create the shard '" + partialPath(mCurrentPath).string() + "'");
        archive_write_free(mArchive);
        mArchive = nullptr;
        return error;
    }
    mCurrentBytes = 0;
    mCurrentSamples.clear();
    return {};
}

Result<void> ShardWriter::finishShard() {
    const int closed = archive_write_close(mArchive);
    Result<void> result;
    if (closed != ARCHIVE_OK) {
        result = archiveError(mArchive, "Cannot finish the shard '" + mCurrentPath.string() + "'");
    }
    archive_write_free(mArchive);
    mArchive = nullptr;
    const fs::path shard[] = {mCurrentPath};
    if (result) {
        result = commitFiles(shard);  // Flushed, then renamed: finished exactly when named so.
    }
    if (!result) {
        std::error_code ec;
        fs::remove(partialPath(mCurrentPath), ec);
        mCurrentSamples.clear();  // Still staged, for the next run.
        return result;
    }
    for (const std::string& sample : mCurrentSamples) {
        mFinishedKeys.insert(shardKey(sample));
        removeSampleFiles(mStaging / fs::path(sample));
    }
    mCurrentSamples.clear();
    ++mNextIndex;
    return {};
}

void ShardWriter::abandonShard() {
    archive_write_free(mArchive);
    mArchive = nullptr;
    std::error_code ec;
    fs::remove(partialPath(mCurrentPath), ec);
    mCurrentSamples.clear();  // Still staged: the next run puts them into a shard.
}

Result<void> ShardWriter::add(const std::string& sampleName) {
    const fs::path folder = mStaging / fs::path(sampleName);
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> files;
    for (const fs::path& file : sampleFiles(folder)) {
        ENCORE_TRY_ASSIGN(auto bytes, readFile(file));
        files.emplace_back(shardKey(sampleName) + "." + file.filename().string(), std::move(bytes));
    }
    std::lock_guard lock(mMutex);
    if (!mArchive) {
        ENCORE_TRY(startShard());
    }
    for (const auto& [name, bytes] : files) {
        archive_entry* entry = archive_entry_new();
        archive_entry_set_pathname(entry, name.c_str());
        archive_entry_set_size(entry, la_int64_t(bytes.size()));
        archive_entry_set_filetype(entry, AE_IFREG);
        archive_entry_set_perm(entry, 0644);
        archive_entry_set_mtime(entry, 0, 0);  // The same shard bytes from the same samples.
        const bool written =
            archive_write_header(mArchive, entry) == ARCHIVE_OK &&
            archive_write_data(mArchive, bytes.data(), bytes.size()) == la_ssize_t(bytes.size());
        archive_entry_free(entry);
        if (!written) {
            Error error = archiveError(mArchive, "Cannot write '" + name + "' to the shard '" +
                                                     partialPath(mCurrentPath).string() + "'");
            abandonShard();
            return error;
        }
        mCurrentBytes += kTarBlock + (bytes.size() + kTarBlock - 1) / kTarBlock * kTarBlock;
    }
    mCurrentSamples.push_back(sampleName);
    if ((mSamplesPerShard > 0 && mCurrentSamples.size() >= mSamplesPerShard) ||
        (mBytesPerShard > 0 && mCurrentBytes >= mBytesPerShard)) {
        return finishShard();
    }
    return {};
}

Result<void> ShardWriter::addStaged() {
    std::set<std::string> staged;    // Whole: with a transforms.json.
    std::set<std::string> leftover;  // Of samples in finished shards, whole or not.
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(mStaging, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (!it->is_regular_file(ec)) {
            continue;
        }
        const std::string sample =
            fs::relative(it->path().parent_path(), mStaging).generic_string();
        if (finished(sample)) {
            // Its shard was renamed, and the run killed while its folder was being removed.
            leftover.insert(sample);
        } else if (it->path().filename() == kTransformsFileName) {
            staged.insert(sample);
        }
    }
    for (const std::string& sample : leftover) {
        removeSampleFiles(mStaging / fs::path(sample));
    }
    pruneEmptyFolders(mStaging);  // Nothing is being written yet.
    fs::create_directories(mStaging, ec);
    for (const std::string& sample : staged) {
        ENCORE_TRY(add(sample));
    }
    return {};
}

Result<void> ShardWriter::close() {
    {
        std::lock_guard lock(mMutex);
        if (mArchive) {
            ENCORE_TRY(finishShard());
        }
    }
    pruneEmptyFolders(mStaging);
    return {};
}

}  // namespace encore::batch
