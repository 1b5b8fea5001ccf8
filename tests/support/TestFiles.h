#pragma once

// Reading what a test's command or batch wrote, to compare outputs byte for byte.

#include <filesystem>
#include <map>
#include <string>

namespace encore::test {

// The file's bytes; empty when it cannot be read.
std::string readBytes(const std::filesystem::path& path);

// Every file under `folder` but failures.jsonl (whose order may differ between runs), by its
// path relative to `folder` ('/'-separated), with its bytes.
std::map<std::string, std::string> filesUnder(const std::filesystem::path& folder);

}  // namespace encore::test
