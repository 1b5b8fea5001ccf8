#pragma once

// WebDataset shards (BatchOptions::shards, shardBytes): the samples of a batch in .tar files,
// OUT/shard-000000.tar ..., each sample's files one after another under the names WebDataset
// groups by key, `<key>.<file>`: "set0/model.000.png", "set0/model.transforms.json",
// "set0/model.metadata.json" (the key is the sample's name with any '.' made '_', since
// WebDataset's key ends at the first dot of the file name).
//
// The batch writes a sample's files as it writes a model folder (ModelWriter), into
// OUT/.staging/<name>/; once the sample is finished there, add() appends its files to the
// current shard, written as shard-N.tar.part through libarchive, which is flushed and renamed to
// shard-N.tar once it holds enough samples (or bytes), or when the batch ends; only then are the
// staged files of its samples removed (their empty folders at the end). So a run killed at any
// moment loses no finished sample and leaves no partial one: the next run (open()) drops the
// partial shard, finds the samples of the finished shards (their member names) finished, and
// appends the staged samples still complete to its first shard before rendering the others.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "encore/core/Result.h"

struct archive;

namespace encore::batch {

inline constexpr const char* kStagingFolderName = ".staging";

// "set0/model" -> "set0/model"; "a.gltf" -> "a_gltf".
std::string shardKey(const std::string& sampleName);

// The members of a tar file, in order (libarchive).
Result<std::vector<std::string>> tarMemberNames(const std::filesystem::path& tar);

class ShardWriter {
  public:
    // A shard is finished after `samplesPerShard` samples (0: no limit) or once it holds
    // `bytesPerShard` bytes (0: no limit), whichever comes first.
    static Result<std::unique_ptr<ShardWriter>> open(const std::filesystem::path& output,
                                                     std::uint64_t samplesPerShard,
                                                     std::uint64_t bytesPerShard);
    ~ShardWriter();
    ShardWriter(const ShardWriter&) = delete;
    ShardWriter& operator=(const ShardWriter&) = delete;

    // Where the batch writes samples before they go into a shard.
    const std::filesystem::path& stagingFolder() const { return mStaging; }
    // Whether a finished shard holds the sample.
    bool finished(const std::string& sampleName) const;
    // Appends the files of the staged sample `sampleName` (every regular file of its folder,
    // transforms.json last) to the current shard. Any thread.
    Result<void> add(const std::string& sampleName);
    // Appends the samples a killed run left finished in the staging folder (those with a
    // transforms.json), after removing what is left of samples a finished shard holds.
    Result<void> addStaged();
    // Finishes the current shard (if it holds a sample) and removes the staging folder's empty
    // folders, and it if it is left empty.
    Result<void> close();

  private:
    ShardWriter() = default;
    Result<void> startShard();   // With mMutex held.
    Result<void> finishShard();  // With mMutex held.
    // After a write error: drops the current shard; its samples stay in the staging folder, and
    // the next run puts them into a shard (as after a kill).
    void abandonShard();  // With mMutex held.

    std::filesystem::path mOutput;
    std::filesystem::path mStaging;
    std::uint64_t mSamplesPerShard = 0;
    std::uint64_t mBytesPerShard = 0;
    std::set<std::string> mFinishedKeys;  // Of the finished shards.

    std::mutex mMutex;
    archive* mArchive = nullptr;  // The current shard, or none.
    std::size_t mNextIndex = 0;
    std::filesystem::path mCurrentPath;  // Its final name.
    std::uint64_t mCurrentBytes = 0;
    std::vector<std::string> mCurrentSamples;  // Their staged folders go with the shard.
};

}  // namespace encore::batch
