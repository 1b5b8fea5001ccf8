#pragma once

// Small generated models written as .glb files, for batch tests that need several inputs.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "encore/batch/BatchInputs.h"

namespace encore::test {

// Writes `count` generated scenes (3 objects, 2 meshes, 2 materials; seeds 1 .. count) into
// `dir` as m<seed>.glb and returns them as batch inputs named m<seed>.
std::vector<batch::BatchInput> writeGeneratedModels(const std::filesystem::path& dir,
                                                    std::uint32_t count);

}  // namespace encore::test
