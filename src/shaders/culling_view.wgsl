// What GPU culling (culling.wgsl) and the visibility strategy's cull (visibility_culling.wgsl)
// share: the frame's culling uniform (render/culling/CullingUniform.h, one struct for both), the
// test of a sphere against the frustum's planes, and the pixels per unit that levels of detail
// are chosen by (render/culling/LodSelection.h). The includer binds `culling`.

struct Culling {
    planes: array<vec4f, 6>,  // xyz: inward unit normal, w: distance; visible when dot >= -radius.
    viewProjection: mat4x4f,
    lodViewCount: u32,       // Entries of lodViews.
    // Pixels that one unit at distance one covers (orthographic: at any distance); 0: levels of
    // detail off.
    lodPixelsPerUnit: f32,
    lodThresholdPixels: f32,
    orthographic: u32,
    occlusion: u32,          // 1: two phases (cullFirstPhase reads last frame's visibility).
    // Subtracted from the distance to the nearest of lodViews: a frame of more views than
    // lodViews holds measures from their centroid, less the farthest view's distance from it.
    lodDistanceSlack: f32,
    // GPU culling's (culling.wgsl):
    viewport: vec2f,         // The depth target's size in pixels.
    phaseArguments: u32,     // Words from a draw's phase 1 arguments to its phase 2 arguments.
    phaseVisible: u32,       // Entries from a draw's phase 1 list to its phase 2 list.
    // Where `indirectArguments` keeps the frame's count of triangles drawn (after all records),
    // and where `visibleInstances` keeps last frame's visibility, one word per slot (after all
    // lists): WebGPU's default limit is 8 storage buffers per stage, and these make 10 otherwise.
    trianglesDrawnWord: u32,
    visibilityBase: u32,
    levelBase: u32,          // Index of the first level record in `records`.
    // The visibility strategy's (visibility_cull.wgsl, visibility_raster.wgsl):
    frustumTest: u32,  // 0 in multi-view frames, whose views each frame the whole scene.
    clusterCulling: u32,  // 1: the raster passes cull clusters (CullingOptions::clusterCulling).
    // 1: the frustum tests read each item's world sphere (visibility_cull.wgsl's worldSpheres).
    worldSpheres: u32,
    // The units buffer's first entry of the cull's list: after the scene's unit table (entry
    // k: the unit that ids k * 256 ... name, VisibilityTables::unitTable), or 0 without one,
    // when ids count the listed units.
    unitListBase: u32,
    // xyz: where the frame's views are (render::LodSelection::kMaxViews); levels of detail are
    // chosen for the nearest.
    lodViews: array<vec4f, 16>,
}

fn largestAxisScale(m: mat4x4f) -> f32 {
    return sqrt(max(max(dot(m[0].xyz, m[0].xyz), dot(m[1].xyz, m[1].xyz)),
                    dot(m[2].xyz, m[2].xyz)));
}

// How far a world-space sphere reaches inside the frustum's plane `plane` (negative: it lies
// wholly outside it).
fn sphereReach(plane: u32, center: vec3f, radius: f32) -> f32 {
    let inward = culling.planes[plane];
    return dot(inward.xyz, center) + inward.w + radius;
}

// Pixels that one object-space unit covers at the point of the world-space box [boxMin, boxMax]
// nearest to a view, for an instance whose largest axis scales by `scale` (0: levels of detail
// off). Both culls choose the coarsest level whose error, times this, stays under
// culling.lodThresholdPixels.
fn lodPixelsPerUnitAt(boxMin: vec3f, boxMax: vec3f, scale: f32) -> f32 {
    var pixelsPerUnit = culling.lodPixelsPerUnit * scale;
    if (culling.orthographic == 0u) {
        var nearest = 3.4e38;
        for (var view = 0u; view < culling.lodViewCount; view++) {
            let position = culling.lodViews[view].xyz;
            nearest = min(nearest, distance(clamp(position, boxMin, boxMax), position));
        }
        pixelsPerUnit /= max(nearest - culling.lodDistanceSlack, 1e-6);
    }
    return pixelsPerUnit;
}
