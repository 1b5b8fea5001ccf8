// encore batch --shards / --shard-size (issue 29): WebDataset .tar shards, read back with
// libarchive: every sample's files under WebDataset's `<key>.<file>` names, one after another, the
// same bytes as the folder layout; and a batch killed with SIGKILL resumes without a duplicated
// or partial sample.

#include <gtest/gtest.h>

#include <archive.h>
#include <archive_entry.h>

#include <fstream>
#include <map>
#include <set>

#include "BatchCommandSupport.h"
#include "BatchOutput.h"
#include "CommandRunner.h"
#include "TestPaths.h"
#include "encore/image/ImageCodec.h"

namespace encore::test {
namespace {

namespace fs = std::filesystem;

struct Member {
    std::string name;
    std::string bytes;
};

// The members of a tar file in order, with their contents.
std::vector<Member> readTar(const fs::path& path) {
    std::vector<Member> members;
    archive* reader = archive_read_new();
    archive_read_support_format_tar(reader);
    EXPECT_EQ(archive_read_open_filename(reader, path.c_str(), 1 << 16), ARCHIVE_OK) << path;
    archive_entry* entry = nullptr;
    int status = ARCHIVE_OK;
    while ((status = archive_read_next_header(reader, &entry)) == ARCHIVE_OK) {
        Member member{archive_entry_pathname(entry), {}};
        member.bytes.resize(std::size_t(archive_entry_size(entry)));
        EXPECT_EQ(archive_read_data(reader, member.bytes.data(), member.bytes.size()),
                  la_ssize_t(member.bytes.size()));
        members.push_back(std::move(member));
    }
    EXPECT_EQ(status, ARCHIVE_EOF) << path << " is not a whole tar file";
    archive_read_free(reader);
    return members;
}

std::vector<fs::path> shardsIn(const fs::path& output) {
    std::vector<fs::path> shards;
    for (const auto& entry : fs::directory_iterator(output)) {
        if (entry.path().extension() == ".tar") {
            shards.push_back(entry.path());
        }
    }
    std::sort(shards.begin(), shards.end());
    return shards;
}

// Every shard's members, as batchOutputFiles names a folder's files ("set0/model/000.png"),
// metadata.json without its timings; fails on a member twice or a sample whose members are
// not one after another.
std::map<std::string, std::string> shardedFiles(const fs::path& output) {
    std::map<std::string, std::string> files;
    std::set<std::string> keysDone;
    std::string currentKey;
    for (const fs::path& shard : shardsIn(output)) {
        for (Member& member : readTar(shard)) {
            const std::size_t slash = member.name.rfind('/');
            const std::size_t dot = member.name.find('.', slash == std::string::npos ? 0 : slash);
            const std::string key = member.name.substr(0, dot);
            const std::string file = member.name.substr(dot + 1);
            if (key != currentKey) {
                EXPECT_TRUE(keysDone.insert(key).second) << key << "'s members are apart";
                currentKey = key;
            }
            const std::string path = key + "/" + file;
            if (file == "metadata.json") {
                member.bytes = metadataWithoutTimings(member.bytes);
            }
            EXPECT_TRUE(files.emplace(path, std::move(member.bytes)).second) << path << " twice";
        }
    }
    return files;
}

TEST(BatchShardsTest, ShardsHoldEverySampleUnderWebDatasetNames) {
    const fs::path input = makeCollection("batch-shards", 3, 4);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-shards-output");
    const std::string options =
        "--views 2 --size 32 --samples 1 --depth --layout objaverse --quiet";
    const CommandResult folders = runEncore(batchArguments(input, output / "folders", options));
    ASSERT_EQ(folders.exitCode, 0) << folders.err;
    const CommandResult sharded =
        runEncore(batchArguments(input, output / "shards", options + " --shards 2"));
    ASSERT_EQ(sharded.exitCode, 0) << sharded.out << sharded.err;
    EXPECT_NE(sharded.out.find("3 rendered, 0 failed"), std::string::npos) << sharded.out;

    // Two models in the first shard (3 models / 2 shards, rounded up), one in the second; the
    // staging folder is gone.
    const std::vector<fs::path> shards = shardsIn(output / "shards");
    ASSERT_EQ(shards.size(), 2u);
    EXPECT_EQ(shards[0].filename(), "shard-000000.tar");
    EXPECT_EQ(shards[1].filename(), "shard-000001.tar");
    EXPECT_FALSE(fs::exists(output / "shards" / ".staging"));
    const auto keysOf = [](const fs::path& shard) {
        std::set<std::string> keys;
        for (const Member& member : readTar(shard)) {
            keys.insert(member.name.substr(0, member.name.find('.', member.name.rfind('/'))));
        }
        return keys;
    };
    EXPECT_EQ(keysOf(shards[0]).size(), 2u);
    EXPECT_EQ(keysOf(shards[1]).size(), 1u);

    // The folder layout's files, byte for byte (failures.jsonl aside).
    auto expected = batchOutputFiles(output / "folders");
    auto actual = shardedFiles(output / "shards");
    EXPECT_EQ(actual.size(), expected.size());
    EXPECT_TRUE(actual == expected) << "the shards hold other bytes than the folders";

    // Run again: every sample is in a shard, nothing is rendered or written.
    const CommandResult again =
        runEncore(batchArguments(input, output / "shards", options + " --shards 2"));
    EXPECT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find("0 rendered, 0 failed, 3 skipped"), std::string::npos) << again.out;
    EXPECT_EQ(shardsIn(output / "shards").size(), 2u);
}

TEST(BatchShardsTest, ShardSizeFinishesAShardOnceItHoldsThatMuch) {
    const fs::path input = makeCollection("batch-shard-size", 3, 4);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-shard-size-output");
    // A byte: every sample finishes its shard.
    const CommandResult run = runEncore(
        batchArguments(input, output, "--views 1 --size 32 --samples 1 --shard-size 1B --quiet"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(shardsIn(output).size(), 3u);
    const CommandResult unit =
        runEncore(batchArguments(input, output, "--views 1 --size 32 --shard-size 3XB --quiet"));
    EXPECT_EQ(unit.exitCode, 2) << unit.err;
    EXPECT_NE(unit.err.find("--shard-size takes a size in bytes"), std::string::npos) << unit.err;
}

// Killed (SIGKILL) once its first shard is finished, then run again: every sample is in exactly
// one shard, whole, with the bytes of a run never killed.
TEST(BatchShardsTest, AKilledShardedBatchResumesWithoutDuplicatedOrPartialSamples) {
    const fs::path input = makeCollection("batch-shards-kill", 8, 40);
    fs::remove(input / "broken.gltf");
    const fs::path output = makeTempDir("batch-shards-kill-output");
    const std::string options = "--views 16 --size 128 --jobs 2 --shards 8 --quiet";
    const fs::path script = input / "kill.sh";
    std::ofstream(script) << "out=\"$1\"; shift\n"
                             "\"$@\" & pid=$!\n"
                             "while kill -0 $pid 2>/dev/null && [ -z \"$(find \"$out\" -name "
                             "'shard-*.tar' 2>/dev/null | head -n 1)\" ]; do sleep 0.01; done\n"
                             "kill -s KILL $pid 2>/dev/null\n"
                             "wait $pid\n";
    const CommandResult killed =
        runEncoreThrough("sh " + quote(script.string()) + " " + quote((output / "run").string()),
                         batchArguments(input, output / "run", options));
    EXPECT_EQ(killed.exitCode, 137) << "not killed (128 + SIGKILL): " << killed.out << killed.err;
    EXPECT_LT(shardsIn(output / "run").size(), 8u) << "the run ended before it was killed";

    const CommandResult rerun = runEncore(batchArguments(input, output / "run", options));
    ASSERT_EQ(rerun.exitCode, 0) << rerun.out << rerun.err;
    EXPECT_TRUE(filesUnder(output / "run", ".part").empty());
    EXPECT_FALSE(fs::exists(output / "run" / ".staging"));
    const CommandResult whole = runEncore(batchArguments(input, output / "whole", options));
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    const auto resumed = shardedFiles(output / "run");
    EXPECT_EQ(resumed.size(), 8u * (16 + 2));
    EXPECT_TRUE(resumed == shardedFiles(output / "whole"));
}

}  // namespace
}  // namespace encore::test
