#pragma once

// What a depth value measures and in which unit (--depth-kind, --depth-unit,
// docs/batch.md#conventions). The GPU writes distances along the camera's axis in the model's
// units (the depth channel, DepthAndId); these turn them into the asked-for kind and unit.

#include <cstdint>
#include <span>
#include <vector>

#include "batch/PassImages.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"
#include "encore/image/ImageCodec.h"

namespace encore::batch {

// How much longer the ray through the centre of pixel (x, y) is than its distance along the
// camera's axis, in an image of width x height seen by `view`: 1 / cos of the ray's angle to the
// axis, sqrt(1 + ((x + 0.5 - cx) / f)^2 + ((y + 0.5 - cy) / f)^2) with transforms.json's
// intrinsics; 1 for an orthographic view (its rays are parallel to the axis).
double rayLengthPerDepth(const ViewCamera& view,
                         std::uint32_t width,
                         std::uint32_t height,
                         std::uint32_t x,
                         std::uint32_t y);

// Turns `depth` (width x height distances along the axis, row after row; infinity where empty)
// into distances along each pixel's ray.
void depthAlongRays(std::span<float> depth,
                    const ViewCamera& view,
                    std::uint32_t width,
                    std::uint32_t height);

// A strip drawn through the depth channel as depth of `kind` seen by `view`, in the units the
// scene is scaled to by `unitsPerModelUnit` (depthUnitsPerModelUnit, or the normalisation's
// scale for a 16-bit PNG's steps), infinity where less than half of the pixel is covered: what
// an EXR depth holds, and what `encore batch` writes and render_views returns share.
std::vector<float> depthOfKind(const FloatStrip& strip,
                               DepthKind kind,
                               float unitsPerModelUnit,
                               const ViewCamera& view);

// The factor from the model's units to the depth's unit: the normalisation's scale
// (`unitsPerModelUnit`) for Normalized, 1 for Model.
float depthUnitsPerModelUnit(DepthUnit unit, float unitsPerModelUnit);

// A 16-bit depth image of `depth` (width x height distances): each distance / `scale` rounded,
// at least 1 step; 0 where it is infinite (empty).
image::ImageGray16 depthStepsOf(std::span<const float> depth,
                                std::uint32_t width,
                                std::uint32_t height,
                                double scale);

}  // namespace encore::batch
