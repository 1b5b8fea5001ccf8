// The visibility strategy's counters for one view (VisibilityStrategy.cpp's byte offsets), reset
// before each view. A view of two-phase occlusion culling runs its raster passes twice: the
// second phase appends its units after the first's and draws its hardware list from where the
// first one's ended (visibility_cull.wgsl's beginSecondPhase).
struct Counters {
    unitCount: atomic<u32>,
    firstUnit: u32,  // This phase's first unit: rasterMain covers [firstUnit, unitCount).
    // Triangles of the levels the cull listed (both phases; some may be back faces, outside
    // the view or degenerate): what GPU culling's count of drawn triangles counts.
    listedTriangles: atomic<u32>,
    secondPhase: u32,  // 1 from beginSecondPhase: the raster passes may read the pyramid.
    // drawIndirect arguments of the hardware pass (byte offset 16): 3 vertices per triangle that
    // this phase listed, from hardwareFirstVertex.
    hardwareVertices: atomic<u32>,
    hardwareInstances: u32,
    hardwareFirstVertex: u32,
    hardwareFirstInstance: u32,
    computeTriangles: atomic<u32>,  // Triangles the compute raster covered pixels of (or not).
    // Beside computeTriangles: one copy per view takes both (VisibilityStrategy::encodeView).
    hardwareTriangles: atomic<u32>,  // Triangles the hardware list took.
    hardwareOverflow: atomic<u32>,  // Triangles the full hardware list could not take.
    workgroupTriangles: atomic<u32>,  // Blocks listed for workgroupMain in this phase.
    // Triangles of the clusters the raster passes culled (frustum, facing, occlusion; both
    // phases): listed, never rasterised.
    culledTriangles: atomic<u32>,
    workgroupRecords: atomic<u32>,  // Triangles set up for workgroupMain in this phase.
    padding1: u32,
    padding2: u32,
    // Not a counter (the copies that reset the counters leave it; the storage bindings of a
    // stage are few): at byte 64, a word per cluster of every level of each item
    // (Item.clusterWords), bit 0 when it was visible in the last two-phase frame, bit 1 while
    // this frame's first phase has taken it (rasterised or culled). visibility_raster.wgsl.
    clusterVisibility: array<u32>,
}
