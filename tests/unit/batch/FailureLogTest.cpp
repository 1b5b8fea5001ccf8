#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "TestPaths.h"
#include "batch/FailureLog.h"

namespace encore::batch {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
    std::ostringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
}

TEST(FailureLogTest, WritesEachFailureAsALineAndKeepsTheEntries) {
    const fs::path path = test::makeTempDir("failure-log") / "failures.jsonl";
    std::ofstream(path) << "an earlier run's line\n";
    auto log = FailureLog::create(path);
    ASSERT_TRUE(log.ok()) << log.error().message;
    log->record("/models/a.glb", "load", "'a.glb' is not a glTF file.");
    log->record("/models/b.glb", "upload", "Out of memory.");
    EXPECT_EQ(contents(path),
              "{\"error\":\"'a.glb' is not a glTF file.\",\"file\":\"/models/a.glb\",\"stage\":"
              "\"load\"}\n{\"error\":\"Out of memory.\",\"file\":\"/models/b.glb\",\"stage\":"
              "\"upload\"}\n");
    const std::vector<Failure> entries = log->entries();
    ASSERT_EQ(entries.size(), 2u);
    EXPECT_EQ(log->count(), 2u);
    EXPECT_EQ(entries[1].file, fs::path("/models/b.glb"));
    EXPECT_EQ(entries[1].stage, "upload");
    EXPECT_EQ(entries[1].error, "Out of memory.");
}

TEST(FailureLogTest, InMemoryLogWritesNoFile) {
    const fs::path dir = test::makeTempDir("failure-log-memory");
    FailureLog log = FailureLog::inMemory();
    log.record(dir / "a.glb", "load", "Broken.");
    EXPECT_EQ(log.count(), 1u);
    EXPECT_EQ(log.entries().at(0).error, "Broken.");
    EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace encore::batch
