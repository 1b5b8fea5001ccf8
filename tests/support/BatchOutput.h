#pragma once

// The files an `encore batch` run wrote, for tests that compare two runs byte for byte: every
// file but failures.jsonl, by its path relative to the output folder, metadata.json without its
// "seconds" and "gpu" (the parts that differ from run to run: times, and what the device thread
// created, which depends on what earlier models left in the pools).

#include <filesystem>
#include <map>
#include <string>

namespace encore::test {

std::map<std::string, std::string> batchOutputFiles(const std::filesystem::path& folder);

// metadata.json's text without its timings and creation counts, as batchOutputFiles keeps it.
std::string metadataWithoutTimings(const std::string& text);

}  // namespace encore::test
