#pragma once

// Command-line options of GPU culling, shared by render, bench and view: occlusion culling
// and levels of detail of the gpu-culling and visibility strategies (render::CullingOptions).

#include <CLI/CLI.hpp>

#include "encore/render/RendererOptions.h"

namespace encore::app {

// --lod-error PIXELS, --no-lod, --no-occlusion, --compute-raster-pixels PIXELS,
// --workgroup-raster-pixels PIXELS, --no-cluster-culling.
void addCullingOptions(CLI::App& command, render::CullingOptions& options);

}  // namespace encore::app
