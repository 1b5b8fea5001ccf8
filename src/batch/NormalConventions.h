#pragma once

// Normals in the asked-for axes and storage (--normal-space, --normal-format,
// docs/batch.md#conventions), from a strip drawn through a normal debug channel and read back as
// floats: n * 0.5 + 0.5 times coverage in RGB (the channels blend over transparent black), the
// coverage in A.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "batch/PassImages.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"

namespace encore::batch {

// What turns a world-space normal into `space`'s for `view`, its camera's axes in `convention`:
// the identity for World; for Camera, the transpose of the camera-to-world rotation. OpenGL's
// and Blender's camera axes are the same (+X right, +Y up, +Z toward the viewer: a surface
// facing the camera reads (0, 0, 1)); OpenCV's negate Y and Z (+Y down, +Z away from the viewer:
// (0, 0, -1)).
glm::dmat3 normalRotation(const ViewCamera& view, NormalSpace space, CameraConvention convention);

// The strip's unit normals turned by `rotation`, and the coverage: RGBA floats, rows packed; all
// 0 where nothing is drawn.
std::vector<float> normalVectors(const FloatStrip& strip, const glm::dmat3& rotation);

// `normals` (normalVectors) as a PNG stores them: n * 0.5 + 0.5 and the coverage, 0 in every
// channel where nothing is drawn.
std::vector<float> mappedNormals(const std::vector<float>& normals);

// The encoded image of `normals` (normalVectors, width x height) in `format`: PNG RGBA of n * 0.5
// + 0.5 with the coverage as alpha, in 8 or 16 bits, or half-float EXR of n and the coverage.
Result<std::vector<std::uint8_t>> encodeNormals(const std::vector<float>& normals,
                                                std::uint32_t width,
                                                std::uint32_t height,
                                                NormalFormat format,
                                                image::PngCompression compression);

}  // namespace encore::batch
