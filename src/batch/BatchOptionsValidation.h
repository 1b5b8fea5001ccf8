#pragma once

// The checks a batch's options pass before anything is created: a batch with bad options fails
// at once, with a sentence naming the values, instead of failing every model.

#include "encore/batch/Batch.h"
#include "encore/core/Result.h"
#include "encore/render/StrategyKind.h"

namespace encore::batch {

// BatchOptions::strategy, or its default: bundles, as `encore render` draws, or
// gpu-culling-bundles with levels of detail (lodErrorPixels > 0), which chooses the levels.
render::StrategyChoice batchStrategy(const BatchOptions& options);

// Succeeds for options a batch can run with. Otherwise an InvalidArgument error for: no pixels
// (width or height 0) or no views; a field of view outside (0, 180) degrees, a distance that is
// not positive or a range of them with its maximum first, a jitter outside [0, 180] degrees; a
// negative environment intensity, a range of intensities or rotations with its maximum first (or
// not finite), an environment folder beside an environment of the renderer options; a negative
// level-of-detail error, or a positive one with a strategy that does not cull on the GPU
// (batchStrategy); visibilityFromTriangles beside an explicit strategy or without
// chooseStrategyPerModel; segmentation with multisampling; albedo, material or segmentation with
// a strategy that does not draw glTF materials in its mesh shader; an EXR depth format without
// depth; a renderer count outside 1..kMaxRenderers. Checks nothing on disk or on the device.
Result<void> validateBatchOptions(const BatchOptions& options);

}  // namespace encore::batch
