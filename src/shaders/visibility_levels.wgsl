// Levels of detail in the visibility strategy's primitive records (render/VisibilityTables.h):
// after the fixed words, the mesh's bounding sphere (levels are chosen as GPU culling chooses
// them, from the instance's sphere), then per coarser level its first triangle counted from
// level 0's first index, its triangle count and its error. A unit's triangles are counted the
// same way, so every pass fetches a coarser level's triangles as level 0's. Needs
// visibility_geometry.wgsl.

const kLevelCount = 30u;  // Coarser levels.
const kMeshSphere = 32u;  // xyz centre, w radius, object space.
const kFirstLevel = 36u;
const kLevelWords = 3u;

struct LevelRange {
    first: u32,  // Triangles counted from level 0's first index.
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

fn levelError(record: u32, level: u32) -> f32 {
    return bitcast<f32>(tables[record + kFirstLevel + (level - 1u) * kLevelWords + 2u]);
}

// The end of the level whose triangles include `triangle` (a unit's first).
fn levelEnd(record: u32, triangle: u32) -> u32 {
    for (var level = field(record, kLevelCount); level > 0u; level--) {
        let range = levelRange(record, level);
        if (triangle >= range.first && triangle - range.first < range.count) {
            return range.first + range.count;
        }
    }
    return field(record, kTriangleCount);
}
