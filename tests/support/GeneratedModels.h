#pragma once

// Small generated models: .glb files for batch tests that need several inputs, and scenes built
// to test one thing.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "encore/batch/BatchInputs.h"

namespace encore::test {

// Writes `count` generated scenes (3 objects, 2 meshes, 2 materials; seeds 1 .. count) into
// `dir` as m<seed>.glb and returns them as batch inputs named m<seed>.
std::vector<batch::BatchInput> writeGeneratedModels(const std::filesystem::path& dir,
                                                    std::uint32_t count);

// A square of half-size `half` facing +Z, cut along the slanted line from (-half, -half) to
// (half, cutY) into a triangle below it (node 0: segmentation id 1) and the rest (node 3: id 4),
// with nodes 1 and 2 drawing nothing: an average of the two ids (2, 3) is no drawn id, and the
// cut crosses many pixels partly. GLB bytes.
std::vector<std::uint8_t> cutSquareGlb(float half, float cutY);

}  // namespace encore::test
