#include <gtest/gtest.h>

#include "TestPaths.h"
#include "encore/core/FileIO.h"

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

}  // namespace
}  // namespace encore
