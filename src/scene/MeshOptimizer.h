#pragma once

// Load-time mesh processing with meshoptimizer, run by the loader as its last stage (see
// LoadOptions) and usable on any SceneData that satisfies the loader's guarantees.
//
// Only indexed triangle lists are touched; points, lines, strips and non-indexed primitives are
// left exactly as they are, and so are triangle lists past the processing limits (more than 2^26
// indices, or more than 65,536 vertices and 8 per index: a primitive reading a small part of a
// large shared vertex buffer). For each indexed triangle list:
//  - Vertex order (optimizeVertexOrder): the triangles are reordered for the post-transform
//    vertex cache (meshopt_optimizeVertexCache, or its FIFO variant with
//    VertexCacheOrder::Fast), then the vertices are renumbered in the order
//    the triangles first use them (meshopt_optimizeVertexFetchRemap), so vertex fetches walk
//    memory forwards. Every vertex stream of the primitive moves together: all attributes and
//    every morph target delta. Vertices no triangle uses keep their place after the used ones,
//    so vertexCount, bounds and accessor min/max stay valid. What is drawn does not change:
//    the same triangles, each with its corners in the same order, over the same vertex values.
//    Two cases keep part of the order:
//      * a primitive whose material blends keeps its triangle order (blending depends on it)
//        and only has its vertices renumbered;
//      * a primitive with a vertex stream that another primitive also reads keeps its vertex
//        order (renumbering would break the other primitive) and only has its triangles
//        reordered.
//  - Clusters (buildClusters, with the vertex order, and not for blending primitives): the
//    triangles of each level are grouped into meshlets of at most Cluster::kMaxTriangles
//    triangles and 128 vertices (meshopt_buildMeshlets), each a run of consecutive triangles,
//    with a bounding sphere and a cone of normals (meshopt_computeMeshletBounds) by which a
//    renderer culls parts of a primitive (Primitive::clusters, LevelOfDetail::clusters). Only
//    the order of the triangles changes: the same triangles, corners in the same order.
//  - Levels of detail (buildLevelsOfDetail): meshopt_simplify halves the triangle count of the
//    previous level again and again, each level within an error bound relative to the
//    primitive's extent, until a level no longer reaches half of the previous triangle count or
//    comes out empty. Levels reuse the primitive's vertices and are vertex-cache ordered too.
//
// Output: each processed primitive gets new index data (level 0 then its levels in one
// bufferView, Primitive::levels describes the layout; each level starts at a multiple of 12
// bytes, a whole number of triangles from level 0's first index) and, when its vertices were
// renumbered, new tightly packed vertex streams (stride rounded up to 4 bytes). All of it goes into
// one buffer appended to the scene. The data the primitive used before stays where it was, unused
// unless another primitive reads it; a buffer that primitives read before and none reads after
// is emptied (Buffer::bytes cleared, its views and accessors left in place but read by no
// primitive: SceneData::accessorBytes returns nothing for them).

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::scene {

struct MeshOptimizerOptions {
    bool optimizeVertexOrder = true;
    // Which cache optimiser orders the triangles of level 0 and of every level of detail.
    VertexCacheOrder vertexCacheOrder = VertexCacheOrder::Thorough;
    bool buildLevelsOfDetail = true;
    // Clusters of every level (with optimizeVertexOrder; see above).
    bool buildClusters = true;
    // The largest deviation a level may have from the full-detail surface, relative to the
    // primitive's extent (meshoptimizer's target_error). The budget covers the whole chain:
    // level k is simplified from level k-1 and the steps' errors add up, so no level exceeds
    // it. It bounds how coarse the chain gets, not which level is drawn (the renderer picks by
    // projected error): at 0.25 the coarsest level is drawn only while the mesh covers fewer
    // than about 4 pixels per pixel of the renderer's threshold, where a few dozen triangles
    // look the same as thousands. A smaller budget stops chains earlier (0.01 leaves about one
    // level on a smooth sphere).
    float maxRelativeError = 0.25f;
    // Keeps the vertices on open borders of a primitive in place (meshopt_SimplifyLockBorder)
    // when its mesh has other primitives, so the seam between two primitives of one surface (a
    // mesh split by material) does not open. Single-primitive meshes simplify their borders too
    // (along the border, within the error): locking them would stop most CAD parts, whose faces
    // are full of open borders, from halving (2CylinderEngine's level 1: 80% of the triangles
    // locked, 52% unlocked).
    bool lockSharedBorders = true;
};

// What optimizeMeshes did, for `encore info` and tests.
struct MeshOptimizerReport {
    std::size_t primitivesReordered = 0;    // Triangles and vertices reordered.
    std::size_t primitivesIndicesOnly = 0;  // Triangles (or vertices) only, as explained above.
    std::size_t levelsBuilt = 0;            // Summed over primitives.
    std::size_t clustersBuilt = 0;          // Of every level, summed over primitives.
    std::size_t buffersReleased = 0;        // Emptied: no primitive reads them any more.
};

// Processes every mesh of `scene`. Fails (naming the mesh and primitive) only on data that
// breaks the loader's guarantees, such as an index past the vertex count, or when the new
// data would pass the loader's limit on materialised bytes; the scene is then unchanged.
Result<MeshOptimizerReport> optimizeMeshes(SceneData& scene,
                                           const MeshOptimizerOptions& options = {});

// Reorders the triangles of one level (`indices`, over `positions`: xyz of each vertex) so that
// each cluster is a run of consecutive triangles (meshopt_buildMeshlets, at most
// Cluster::kMaxTriangles triangles and 128 vertices each, their spheres and normal cones from
// meshopt_computeMeshletBounds) and returns the clusters, their first triangles counted from the
// level's first. The triangles stay the same, each with its corners in the same order. Returns
// nothing, `indices` unchanged, for no triangles, no positions, or positions past 1e9 in
// magnitude (meshoptimizer's bounds would overflow there). `scan`: clusters of
// consecutive triangles in the order they have (meshopt_buildMeshletsScan; with the
// vertex-cache order, local enough), for VertexCacheOrder::Fast loads: on a dense generated model
// the spatial builder tripled the load (on the H100's host 50 -> 330 ms per model), the scan
// costs nothing measurable, at some cost in culling (a sphere seen whole: 54% of its triangles
// set up against 44%).
std::vector<Cluster> orderIntoClusters(std::vector<std::uint32_t>& indices,
                                       const std::vector<glm::vec4>& positions,
                                       bool scan = false);

}  // namespace encore::scene
