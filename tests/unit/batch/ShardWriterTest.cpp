#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.h"
#include "batch/ShardWriter.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

// A finished sample in the staging folder: two images, metadata.json and transforms.json.
void stage(const ShardWriter& shards, const std::string& name) {
    const fs::path folder = shards.stagingFolder() / name;
    fs::create_directories(folder);
    for (const char* file : {"001.png", "000.png", "transforms.json", "metadata.json"}) {
        std::ofstream(folder / file) << name << "/" << file;
    }
}

TEST(ShardWriterTest, KeysEndAtTheFirstDotOfTheFileName) {
    EXPECT_EQ(shardKey("set0/model"), "set0/model");
    EXPECT_EQ(shardKey("a.gltf"), "a_gltf");
    EXPECT_EQ(shardKey("v1.2/shoe@red.dark"), "v1_2/shoe@red_dark");
}

TEST(ShardWriterTest, SamplesGoIntoShardsWholeAndTheirFoldersGoWithTheShard) {
    const fs::path output = test::makeTempDir("shard-writer");
    auto shards = ShardWriter::open(output, 2, 0);
    ASSERT_TRUE(shards.ok()) << shards.error().message;
    for (const char* name : {"a/one", "a/two", "b.glb"}) {
        stage(**shards, name);
        ASSERT_TRUE((*shards)->add(name).ok());
    }
    // The first shard is finished (two samples), their files gone; the third is staged.
    EXPECT_TRUE(fs::exists(output / "shard-000000.tar"));
    EXPECT_TRUE(fs::exists(output / "shard-000001.tar.part"));
    EXPECT_FALSE(fs::exists((*shards)->stagingFolder() / "a" / "one" / "000.png"));
    EXPECT_FALSE(fs::exists((*shards)->stagingFolder() / "a" / "two" / "transforms.json"));
    EXPECT_TRUE(fs::exists((*shards)->stagingFolder() / "b.glb" / "transforms.json"));
    EXPECT_TRUE((*shards)->finished("a/two"));
    EXPECT_FALSE((*shards)->finished("b.glb"));
    auto members = tarMemberNames(output / "shard-000000.tar");
    ASSERT_TRUE(members.ok()) << members.error().message;
    EXPECT_EQ(*members,
              (std::vector<std::string>{"a/one.000.png", "a/one.001.png", "a/one.metadata.json",
                                        "a/one.transforms.json", "a/two.000.png", "a/two.001.png",
                                        "a/two.metadata.json", "a/two.transforms.json"}));

    // Stopped here (as by SIGKILL): the next writer drops the partial shard, takes the finished
    // one's samples as finished and puts the staged sample into its first shard.
    shards->reset();
    auto resumed = ShardWriter::open(output, 2, 0);
    ASSERT_TRUE(resumed.ok()) << resumed.error().message;
    EXPECT_FALSE(fs::exists(output / "shard-000001.tar.part"));
    EXPECT_TRUE((*resumed)->finished("a/one"));
    EXPECT_FALSE((*resumed)->finished("b.glb"));
    ASSERT_TRUE((*resumed)->addStaged().ok());
    ASSERT_TRUE((*resumed)->close().ok());
    EXPECT_FALSE(fs::exists((*resumed)->stagingFolder()));
    auto last = tarMemberNames(output / "shard-000001.tar");
    ASSERT_TRUE(last.ok()) << last.error().message;
    EXPECT_EQ(*last, (std::vector<std::string>{"b_glb.000.png", "b_glb.001.png",
                                               "b_glb.metadata.json", "b_glb.transforms.json"}));
    EXPECT_TRUE((*resumed)->finished("b.glb"));
}

// Killed while a finished shard's samples were being removed: what is left of them goes, and a
// sample in a folder below another's keeps its files when the other's are removed.
TEST(ShardWriterTest, LeftoversOfFinishedSamplesGoAndNestedSamplesStay) {
    const fs::path output = test::makeTempDir("shard-writer-leftovers");
    {
        auto shards = ShardWriter::open(output, 1, 0);
        ASSERT_TRUE(shards.ok());
        stage(**shards, "a");
        stage(**shards, "a/b");
        ASSERT_TRUE((*shards)->add("a").ok());  // A shard of its own, finished.
        EXPECT_TRUE(fs::exists((*shards)->stagingFolder() / "a" / "b" / "000.png"));
        std::ofstream((*shards)->stagingFolder() / "a" / "001.png") << "left by a kill";
    }
    auto resumed = ShardWriter::open(output, 1, 0);
    ASSERT_TRUE(resumed.ok());
    ASSERT_TRUE((*resumed)->addStaged().ok());  // "a/b", whole, into shard 1.
    ASSERT_TRUE((*resumed)->close().ok());
    EXPECT_FALSE(fs::exists((*resumed)->stagingFolder()));
    auto members = tarMemberNames(output / "shard-000001.tar");
    ASSERT_TRUE(members.ok());
    EXPECT_EQ(members->size(), 4u);
    EXPECT_EQ(members->front(), "a/b.000.png");
}

TEST(ShardWriterTest, AShardOfTheSizeAskedForIsFinished) {
    const fs::path output = test::makeTempDir("shard-writer-size");
    // Each sample takes 4 members of 512 bytes of header and 512 of data: 4096 bytes.
    auto shards = ShardWriter::open(output, 0, 8000);
    ASSERT_TRUE(shards.ok());
    for (const char* name : {"m1", "m2", "m3"}) {
        stage(**shards, name);
        ASSERT_TRUE((*shards)->add(name).ok());
    }
    EXPECT_TRUE(fs::exists(output / "shard-000000.tar"));  // 8192 bytes: full.
    EXPECT_FALSE(fs::exists(output / "shard-000001.tar"));
    ASSERT_TRUE((*shards)->close().ok());
    auto members = tarMemberNames(output / "shard-000001.tar");
    ASSERT_TRUE(members.ok());
    EXPECT_EQ(members->size(), 4u);
}

TEST(ShardWriterTest, AnUnreadableShardIsAnError) {
    const fs::path output = test::makeTempDir("shard-writer-bad");
    std::ofstream(output / "shard-000000.tar") << "not a tar file";
    auto shards = ShardWriter::open(output, 1, 0);
    ASSERT_FALSE(shards.ok());
    EXPECT_NE(shards.error().message.find("shard-000000.tar"), std::string::npos)
        << shards.error().message;
}

}  // namespace
}  // namespace encore::batch
