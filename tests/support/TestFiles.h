#pragma once

// Reading what a test's command wrote (BatchOutput.h compares whole batch outputs).

#include <filesystem>
#include <string>

namespace encore::test {

// The file's bytes; empty when it cannot be read.
std::string readBytes(const std::filesystem::path& path);

}  // namespace encore::test
