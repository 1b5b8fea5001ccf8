#pragma once

// A small WGSL preprocessor, so that shader variants are composed from one source:
//   #include "file.wgsl"    inserts another file (each file at most once per composition)
//   #if FLAG / #if !FLAG    keeps the following lines when FLAG is (not) defined
//   #elif FLAG / #else / #endif, nested to any depth
// Flags are plain names; anything else after #if is an error, as are unknown directives,
// unbalanced blocks and missing includes. Errors name the file and line.

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "encore/core/Result.h"

namespace encore::shaders {

// Returns a file's text by name, or nullopt when there is no such file.
using FileLookup = std::function<std::optional<std::string_view>(std::string_view name)>;

Result<std::string> composeShader(std::string_view fileName,
                                  const std::set<std::string, std::less<>>& flags,
                                  const FileLookup& lookup);

// composeShader over the embedded .wgsl files.
Result<std::string> composeEmbeddedShader(std::string_view fileName,
                                          const std::set<std::string, std::less<>>& flags);

}  // namespace encore::shaders
