// Levels of detail and clusters in the visibility strategy's primitive records
// (render/visibility/VisibilityTables.h): after the fixed words, the mesh's bounding sphere (levels
// are chosen as GPU culling chooses them, from the instance's sphere), level 0's clusters, then per
// coarser level its first triangle counted from level 0's first index, its triangle count, its
// error and its clusters. A cluster's triangles are counted the same way, so every pass fetches a
// coarser level's triangles as level 0's. Needs visibility_geometry.wgsl.

const kLevelCount = 30u;     // Coarser levels.
const kMeshSphere = 32u;     // xyz centre, w radius, object space.
const kLevelClusters = 36u;  // Level 0's first cluster record (word index) and cluster count.
const kFirstLevel = 38u;
// First triangle, triangles, error bits, first cluster record (word index), clusters.
const kLevelWords = 5u;

struct LevelRange {
    first: u32,  // Triangles counted from level 0's first index.
    count: u32,
}

struct ClusterRange {
    first: u32,  // Word index of the first cluster record; the others follow it.
    count: u32,
}

// Level 0 is the mesh as loaded; 1 and more are the coarser levels.
fn levelRange(record: u32, level: u32) -> LevelRange {
    if (level == 0u) {
        return LevelRange(0u, field(record, kTriangleCount));
    }
    let base = record + kFirstLevel + (level - 1u) * kLevelWords;
    return LevelRange(tables[base], tables[base + 1u]);
}

fn levelClusters(record: u32, level: u32) -> ClusterRange {
    var base = record + kLevelClusters;
    if (level > 0u) {
        base = record + kFirstLevel + (level - 1u) * kLevelWords + 3u;
    }
    return ClusterRange(tables[base], tables[base + 1u]);
}

fn levelError(record: u32, level: u32) -> f32 {
    return bitcast<f32>(tables[record + kFirstLevel + (level - 1u) * kLevelWords + 2u]);
}
