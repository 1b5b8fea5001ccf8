#pragma once

// What the visibility strategy's shaders read about the scene (visibility_geometry.wgsl): a
// record per primitive that the compute path draws (where its indices and attributes lie in the
// GPU scene's first shared geometry buffer, their formats, material, shading bin, bounds) and a
// list of items, one per (instance, such primitive), in instance-buffer order (instance slot,
// record, first word of its clusters' visibility, mirrored). Built once per scene from the
// GpuScene; the strategy uploads `words`.
//
// Levels of detail (visibility_levels.wgsl): after its kPrimitiveWords, a record holds its
// mesh's bounding sphere (as CullingBounds bounds an instance, so that levels are chosen as GPU
// culling chooses them), level 0's clusters and its coarser levels, each a range of triangles
// counted from level 0's first index (the levels lie after level 0 in the same index data), its
// triangle count, its error and its clusters.
//
// Clusters (visibility_geometry.wgsl's kCluster* words, after the records): each level's
// clusters (scene::Cluster, the loader's meshlets) as a run of kClusterWords records: first
// triangle (counted from level 0's first index), triangle count (at most kUnitTriangles),
// bounding sphere and normal cone, object space. The cull lists an item's clusters of its level
// as units, the raster culls each on its own. A level without clusters from the loader (not
// processed, blending material, clusters that do not cover it exactly) gets runs of
// kUnitTriangles triangles whose radius (kNeverCulled) culls nothing.
//
// The compute path takes opaque, static triangle lists whose data lies in the first shared
// buffer within `maxGeometryBytes`; the rest (MASK and BLEND materials, skinned or morphed
// primitives, other topologies, data elsewhere) is drawn by the hardware as `materials` draws
// it, so nothing goes missing.

#include <cstdint>
#include <vector>

#include "render/GpuScene.h"
#include "render/visibility/MaterialBins.h"

namespace encore::render {

struct VisibilityTables {
    static constexpr std::uint32_t kItemWords = 4;        // visibility_geometry.wgsl's.
    static constexpr std::uint32_t kPrimitiveWords = 32;  // Likewise.
    static constexpr std::uint32_t kUnitTriangles = 256;  // Likewise.
    // visibility_levels.wgsl's.
    static constexpr std::uint32_t kLevelCount = 30;     // Coarser levels, in the fixed part.
    static constexpr std::uint32_t kMeshSphere = 32;     // After the fixed part: 4 words.
    static constexpr std::uint32_t kLevelClusters = 36;  // Level 0's first cluster, clusters.
    static constexpr std::uint32_t kFirstLevel = 38;     // Then kLevelWords per coarser level.
    // First triangle, triangles, error bits, first cluster (word index), clusters.
    static constexpr std::uint32_t kLevelWords = 5;
    static constexpr std::uint32_t kClusterWords = 13;  // visibility_geometry.wgsl's.
    // In a cluster's triangle count: the only cluster of its level (its item is culled as a
    // whole by the item tests, so the two occlusion phases need nothing per cluster for it).
    static constexpr std::uint32_t kClusterAlone = 1u << 31;
    static constexpr float kNeverCulled = 1e30f;  // A cluster radius that culls nothing.

    // Items (kItemWords each), then primitive records, then cluster records.
    std::vector<std::uint32_t> words;
    std::uint32_t itemCount = 0;
    // Units of all items (the most clusters of any level of each): the unit list's capacity.
    std::uint64_t unitCount = 0;
    std::uint64_t clusterCount = 0;  // Cluster records (of every level of every primitive).
    // Per cluster of every level of each item, in Item.clusterWords order: (item, word index of
    // its cluster record). A visibility-buffer id counts its unit by this index, not by the
    // cull's order of listing, so that a depth tie between coplanar triangles (the larger id
    // wins) goes the same way every run: the strategy's files are reproducible. Empty when the
    // ids would not fit 32 bits (kMaxStableUnits): units are then counted in listed order.
    std::vector<std::uint32_t> unitTable;
    static constexpr std::uint64_t kMaxStableUnits = (std::uint64_t(1) << 32) / kUnitTriangles;
    // The units buffer's entry where the cull's list starts: after the unit table.
    std::uint32_t unitListBase() const { return std::uint32_t(unitTable.size() / 2); }
    // A word per cluster of every level of each item, for the item's clusters' visibility last
    // frame (visibility_raster.wgsl); an item's words start at its third word.
    std::uint64_t clusterVisibilityWords = 0;
    std::uint64_t triangleCount = 0;  // Triangles of all items.
    // [mesh][primitive]: whether the compute path draws it (for every instance of the mesh).
    std::vector<std::vector<bool>> computePath;
    // The shading bins (MaterialBins.h: leader * 2 + 1 with a bound TANGENT) that some item
    // uses, ascending.
    std::vector<std::uint32_t> bins;
    std::uint32_t binCount = 0;  // 2 * materials: the bin table's size.
    // The grouping of the materials that the records' bin words follow, and the word index of
    // each primitive record some item uses.
    MaterialBins materialBins;
    std::vector<std::uint32_t> usedRecords;
};

VisibilityTables buildVisibilityTables(const GpuScene& scene, std::uint64_t maxGeometryBytes);

// Rewrites each used record's bin word after `materialBins` (a material's textures replaced
// regroup them) and the bins in use; returns the word indices it changed.
std::vector<std::uint32_t> assignShadingBins(VisibilityTables& tables, MaterialBins materialBins);

}  // namespace encore::render
