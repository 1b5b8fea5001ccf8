#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>

#include "TestPaths.h"
#include "core/FileIO.h"

namespace encore {
namespace {

TEST(FileIOTest, RoundTripsBytes) {
    auto dir = test::makeTempDir("fileio");
    const std::vector<std::uint8_t> bytes = {0, 1, 2, 255};
    ASSERT_TRUE(writeFile(dir / "a.bin", bytes).ok());
    auto read = readFile(dir / "a.bin");
    ASSERT_TRUE(read.ok());
    EXPECT_EQ(*read, bytes);
}

TEST(FileIOTest, MissingFileNamesThePath) {
    auto read = readFile("/nonexistent/encore/file.glb");
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::FileNotFound);
    EXPECT_NE(read.error().message.find("/nonexistent/encore/file.glb"), std::string::npos);
}

// A FIFO would block open() until a writer comes (a batch that never ends); a device may never
// end. Both are refused at once, naming what they are.
TEST(FileIOTest, OnlyRegularFilesAreRead) {
    auto dir = test::makeTempDir("fileio-fifo");
    ASSERT_EQ(::mkfifo((dir / "pipe.bin").c_str(), 0600), 0);
    auto read = readFile(dir / "pipe.bin");
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::FileUnreadable);
    EXPECT_NE(read.error().message.find("is a FIFO, not a regular file"), std::string::npos)
        << read.error().message;
    read = readFile("/dev/zero");
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("is a device"), std::string::npos) << read.error().message;
    // A link to a regular file is read.
    ASSERT_TRUE(writeFile(dir / "a.bin", std::vector<std::uint8_t>{7, 8}).ok());
    std::filesystem::create_symlink(dir / "a.bin", dir / "link.bin");
    read = readFile(dir / "link.bin");
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->size(), 2u);
}

TEST(FileIOTest, DirectoryIsRefused) {
    auto dir = test::makeTempDir("fileio-dir");
    auto read = readFile(dir);
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::FileUnreadable);
    EXPECT_NE(read.error().message.find("is a directory"), std::string::npos);
}

TEST(FileIOTest, WriteToMissingDirectoryFails) {
    const std::vector<std::uint8_t> bytes = {1};
    auto written = writeFile("/nonexistent/encore/out.bin", bytes);
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().code, ErrorCode::IoError);
}

TEST(FileIOTest, AtomicWriteLeavesNoPartialFile) {
    auto dir = test::makeTempDir("fileio-atomic");
    ASSERT_TRUE(writeFile(dir / "a.bin", std::vector<std::uint8_t>{9, 9}).ok());
    const std::vector<std::uint8_t> bytes = {1, 2, 3};
    ASSERT_TRUE(writeFileAtomically(dir / "a.bin", bytes).ok());
    EXPECT_EQ(*readFile(dir / "a.bin"), bytes);
    EXPECT_EQ(partialPath(dir / "a.bin"), dir / "a.bin.part");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.bin.part"));
}

TEST(FileIOTest, AtomicWriteToMissingDirectoryFails) {
    auto written = writeFileAtomically("/nonexistent/encore/out.bin", std::vector<std::uint8_t>{1});
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().code, ErrorCode::IoError);
}

// A group of files exists under partial names until commitFiles gives all of them their names.
TEST(FileIOTest, PartialFilesAppearWhenCommitted) {
    auto dir = test::makeTempDir("fileio-group");
    const std::vector<std::filesystem::path> paths = {dir / "000.png", dir / "001.png"};
    ASSERT_TRUE(writePartialFile(paths[0], std::vector<std::uint8_t>{1, 2}).ok());
    ASSERT_TRUE(writePartialFile(paths[1], std::vector<std::uint8_t>{3}).ok());
    EXPECT_FALSE(std::filesystem::exists(paths[0]));
    EXPECT_FALSE(std::filesystem::exists(paths[1]));
    EXPECT_TRUE(std::filesystem::exists(dir / "001.png.part"));
    ASSERT_TRUE(commitFiles(paths).ok());
    EXPECT_EQ(*readFile(paths[0]), (std::vector<std::uint8_t>{1, 2}));
    EXPECT_EQ(*readFile(paths[1]), (std::vector<std::uint8_t>{3}));
    EXPECT_FALSE(std::filesystem::exists(dir / "000.png.part"));
    EXPECT_FALSE(std::filesystem::exists(dir / "001.png.part"));
}

// A missing partial file fails the commit, naming it, and renames none of the group.
TEST(FileIOTest, CommitOfAMissingPartialFileFails) {
    auto dir = test::makeTempDir("fileio-group-missing");
    ASSERT_TRUE(writePartialFile(dir / "a.png", std::vector<std::uint8_t>{1}).ok());
    const std::vector<std::filesystem::path> paths = {dir / "a.png", dir / "b.png"};
    auto committed = commitFiles(paths);
    ASSERT_FALSE(committed.ok());
    EXPECT_EQ(committed.error().code, ErrorCode::IoError);
    EXPECT_NE(committed.error().message.find("b.png.part"), std::string::npos)
        << committed.error().message;
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    EXPECT_FALSE(writePartialFile("/nonexistent/encore/c.png", std::vector<std::uint8_t>{1}).ok());
}

}  // namespace
}  // namespace encore
