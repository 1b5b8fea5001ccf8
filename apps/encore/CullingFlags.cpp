#include "CullingFlags.h"

namespace encore::app {

void addCullingOptions(CLI::App& command, render::CullingOptions& options) {
    command
        .add_option("--lod-error", options.lodErrorPixels,
                    "gpu-culling and visibility strategies: draw each instance at the coarsest "
                    "level of detail whose simplification error, projected on the screen, stays "
                    "under this many pixels")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command.add_flag("!--no-lod", options.levelsOfDetail,
                     "gpu-culling and visibility strategies: draw every instance at full detail");
    command.add_flag("!--no-occlusion", options.occlusion,
                     "gpu-culling and visibility strategies: cull against the frustum only (no "
                     "two-phase occlusion culling)");
    command
        .add_option("--compute-raster-pixels", options.computeRasterPixels,
                    "visibility strategy: one compute thread rasterises each triangle whose "
                    "screen bounds span at most this many pixels each way")
        ->check(CLI::Range(0.0f, 64.0f))
        ->capture_default_str();
    command
        .add_option("--workgroup-raster-pixels", options.workgroupRasterPixels,
                    "visibility strategy: a compute workgroup rasterises, in 8x8 tiles, each "
                    "larger triangle up to this many pixels each way; larger ones, and those "
                    "crossing the near or far plane, go to the hardware, except at 8192 (the "
                    "default), where compute clips them and no hardware raster pass runs (0 "
                    "with --compute-raster-pixels 0: all in hardware)")
        ->check(CLI::Range(0.0f, 8192.0f))
        ->capture_default_str();
    command.add_flag("!--no-cluster-culling", options.clusterCulling,
                     "visibility strategy: rasterise every cluster of each drawn instance (no "
                     "culling of clusters by frustum, facing and occlusion)");
}

}  // namespace encore::app
