#pragma once

// `encore batch`'s pass flags beyond --normals and --depth: --albedo, --material,
// --segmentation [--segmentation-by], --depth-format, --hdr, --pass-frames
// (docs/batch.md#passes).

#include <string>

#include <CLI/CLI.hpp>

#include "encore/batch/ViewImages.h"

namespace encore::app {

struct BatchPassOptions {
    bool albedo = false;
    bool material = false;
    bool segmentation = false;
    bool hdr = false;
    bool passFrames = false;  // --pass-frames: one frame per pass (PassDrawing::Frames).
    std::string segmentationBy = "node";
    std::string depthFormat = "png";
};

// Adds the flags to `command`; `depth` is its --depth flag, which --depth-format needs.
void addBatchPassOptions(CLI::App& command, BatchPassOptions& options, CLI::Option* depth);

// Sets the passes in `images` (whose normals and depth the caller sets).
void applyBatchPassOptions(const BatchPassOptions& options, batch::ExtraImages& images);

}  // namespace encore::app
