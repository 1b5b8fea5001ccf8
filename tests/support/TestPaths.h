#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace encore::test {

// ../shared/models beside the clone, or nullopt when it is absent (tests then GTEST_SKIP with a
// message saying so).
std::optional<std::filesystem::path> sharedModelsDir();

// ../shared/reference (renders by the Khronos glTF Sample Renderer, with list.txt), or nullopt.
std::optional<std::filesystem::path> sharedReferenceDir();

// The clone's root (its docs/, for tests that check them against the code).
std::filesystem::path sourceDir();

// A fresh, empty directory under the system temp dir, unique to this process and name.
std::filesystem::path makeTempDir(const std::string& name);

}  // namespace encore::test
