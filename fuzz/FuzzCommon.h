#pragma once

// Shared by the libFuzzer targets: how they call the loader, and how they report a broken
// promise of SceneData.h (an accepted scene that a renderer could not use safely).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "encore/scene/SceneData.h"

namespace encore::fuzz {

// External uris resolve against a directory that does not exist, so that inputs cannot reach
// the repository's files (absolute paths are still opened; see docs/fuzzing.md).
inline Result<scene::SceneData> loadFuzzInput(const std::uint8_t* data, std::size_t size) {
    scene::LoadOptions options;
    options.decodeImages = true;
    return scene::loadSceneFromMemory(std::span<const std::uint8_t>(data, size),
                                      "/nonexistent/encore-fuzz", "fuzz-input", options);
}

// Loads the bytes, then does with an accepted scene what a renderer does on the CPU, checking
// the promises of SceneData.h (PrepareChecks.cpp): the body of encore_fuzz_prepare and
// encore_fuzz_numbers. A broken promise aborts through ENCORE_FUZZ_CHECK.
void loadAndPrepare(const std::uint8_t* data, std::size_t size);

// A broken invariant is a finding: print it and abort so that libFuzzer saves the input.
[[noreturn]] inline void invariantFailed(const char* what, const char* file, int line) {
    std::fprintf(stderr, "%s:%d: SceneData invariant broken: %s\n", file, line, what);
    std::abort();
}

}  // namespace encore::fuzz

#define ENCORE_FUZZ_CHECK(condition)                                         \
    do {                                                                     \
        if (!(condition))                                                    \
            ::encore::fuzz::invariantFailed(#condition, __FILE__, __LINE__); \
    } while (false)
