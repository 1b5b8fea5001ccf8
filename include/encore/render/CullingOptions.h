#pragma once

// How the GPU-culling strategies choose what to draw, changeable between frames (the culling pass
// reads them from a uniform each frame, so recorded bundles stay valid).

namespace encore::render {

struct CullingOptions {
    // Two-phase occlusion culling: draw what was visible last frame, build a depth pyramid from
    // it, then draw whatever else the pyramid does not hide. Only for frames of one view (a
    // multi-view frame culls against the frustum only).
    bool occlusion = true;
    // Draw each instance at the coarsest level of detail whose simplification error, projected
    // on the screen, stays under `lodErrorPixels` (level 0, the mesh as loaded, when off).
    bool levelsOfDetail = true;
    float lodErrorPixels = 1.0f;
    // The visibility strategy: triangles whose screen bounds span at most computeRasterPixels
    // each way are rasterised in compute by one thread (at most 64), those up to
    // workgroupRasterPixels by a workgroup in 8x8 tiles (at most 8192), larger ones by the
    // hardware, as do triangles crossing the near or far plane. 6 measured fastest on the H100
    // (docs/visibility-performance.md).
    float computeRasterPixels = 6.0f;
    float workgroupRasterPixels = 8192.0f;
    // The visibility strategy: each cluster (meshlet) of a drawn item is culled on its own
    // against the frustum, by its cone of normals (all its triangles facing away) and, in the
    // second occlusion phase, against the depth pyramid. Off: every triangle of a listed item is
    // rasterised (the same picture; for comparisons).
    bool clusterCulling = true;

    bool operator==(const CullingOptions&) const = default;
};

}  // namespace encore::render
