enable atomic_vec2u_min_max;

// The visibility strategy's raster passes, for one view (or one phase of it: visibility_cull.wgsl
// lists the units):
//   rasterMain     a workgroup per batch of units (clusters of items): a thread per unit culls
//                  its cluster (clusterCulled: frustum, facing, and in the second phase
//                  occlusion), then the kept clusters' triangles are dealt out a thread each:
//                  clip, cull back faces, snap to 1/256 pixel and cover pixel centres with edge
//                  functions under the top-left rule (at each of the pixel's samples,
//                  VisibilityParams.samples), writing (depth, id) with a 64-bit atomic max of
//                  (id, ~depth bits), so the nearest depth wins. Triangles whose screen bounds
//                  exceed params.maxComputePixels are listed for workgroupMain in blocks; those
//                  that cross the near or far plane, or exceed params.maxWorkgroupPixels, or
//                  find the block list full, are listed whole: for the hardware pass
//                  (visibility_hardware.wgsl), or with params.computeTakesAll for workgroupMain.
//   workgroupMain  a workgroup per listed block of a triangle (up to kBlockPixels squared),
//                  covering it in 8x8 tiles; then, with params.computeTakesAll, kWholeParts
//                  workgroups per triangle listed whole, which each clip (near and far planes,
//                  a guard band) and cover a share of its tiles.
#include "frame.wgsl"
#include "visibility_geometry.wgsl"
#include "visibility_samples.wgsl"

#include "visibility_levels.wgsl"
#include "visibility_counters.wgsl"
#include "pyramid_occlusion.wgsl"
#include "visibility_culling.wgsl"
#include "visibility_batch.wgsl"
#include "visibility_edges.wgsl"
#include "visibility_clip.wgsl"

@group(1) @binding(4) var<storage, read_write> units: array<vec2u>;
@group(1) @binding(5) var<storage, read_write> counters: Counters;
@group(1) @binding(6) var<storage, read_write> hardwareList: array<u32>;
@group(1) @binding(7) var<storage, read_write> visibility: array<atomic<vec2u>>;
// Triangles too large for one thread, which workgroupMain covers. In the first
// params.workgroupBlocks entries their blocks, (record, block): a triangle's bounds split into
// blocks of kBlockPixels squared, so that no workgroup walks a large triangle alone while the
// others have finished; kNoEntry marks a slot left empty. Then params.workgroupRecords records
// of kRecordEntries entries: each triangle as rasterMain set it up, which its blocks read
// rather than setting it up again (on the H100 the setup per block was a third of the pass).
@group(1) @binding(9) var<storage, read_write> workgroupList: array<vec2u>;
const kRecordEntries = 8u;
// Measured on the H100 (docs/visibility.md): blocks of 32 against 16, 64 and whole triangles.
const kBlockPixels = 32;
const kNoEntry = 0xffffffffu;

// rasterMain and workgroupMain (and the shading pass) run as a fixed grid of workgroups that
// strides over the work the cull listed: direct dispatches. An indirect dispatch sized by the
// GPU would be exact, but Dawn validates each one with a dispatch of its own and a bind group
// made while encoding: 0.8 of the 0.9 ms CPU frame on the H100 (docs/visibility.md).

// Sub-pixel precision of the snapped vertices, as the hardware's (8 bits).
const kSubpixels = 256.0;

// Lists triangle `id` whole (the hardware list): for the hardware pass, or where the compute
// raster takes every triangle, for workgroupMain to clip and cover. Returns whether the compute
// raster took it.
fn listWhole(id: u32) -> bool {
    let slot = (counters.hardwareFirstVertex + atomicAdd(&counters.hardwareVertices, 3u)) / 3u;
    if (slot >= params.hardwareCapacity) {
        atomicAdd(&counters.hardwareOverflow, 1u);
        return false;
    }
    hardwareList[slot] = id;
    if (params.computeTakesAll != 0u) {
        return true;
    }
    atomicAdd(&counters.hardwareTriangles, 1u);
    return false;
}

fn windowPosition(clip: vec4f) -> vec3f {
    let ndc = clip.xyz / clip.w;
    let halfWidth = f32(params.viewportWidth) * 0.5;
    let halfHeight = f32(params.viewportHeight) * 0.5;
    return vec3f(ndc.x * halfWidth + (f32(params.viewportX) + halfWidth),
                 -ndc.y * halfHeight + (f32(params.viewportY) + halfHeight), ndc.z);
}

// Where prepareTriangle sends a triangle.
const kRouteNone = 0u;       // Nothing to draw: outside, back-facing, degenerate, or handed on.
const kRouteThread = 1u;     // Small: one thread covers its pixels.
const kRouteWorkgroup = 2u;  // Larger: a workgroup covers its pixels in 8x8 tiles.
const kRouteWhole = 3u;      // Crossing the near or far plane, or too large: listed whole.

// A triangle set up for the compute raster: vertices snapped to 1/256 pixel relative to its
// first pixel, wound so that inside is positive, with the fill rule's biases.
struct RasterTriangle {
    route: u32,
    first: vec2i,  // The pixels whose centres it may cover, inside the viewport.
    last: vec2i,
    v0: vec2i,
    v1: vec2i,
    v2: vec2i,
    wide: bool,  // Evaluated in 64 bits: over kNarrowPixels across.
    // Depth at the first pixel's corner and its change per pixel in x and y: a plane through
    // the vertices as projected, not as snapped, as the hardware interpolates depth.
    depth: vec3f,
    nearest: f32,  // The nearest depth of its vertices.
    bias: vec3i,
}

// The fill rule's bias of each edge (wound so that inside is positive).
fn triangleBias(t: RasterTriangle) -> vec3i {
    return vec3i(topLeftBias(t.v1, t.v2), topLeftBias(t.v2, t.v0), topLeftBias(t.v0, t.v1));
}

fn facesTheCamera(c0: vec4f, c1: vec4f, c2: vec4f, item: Item) -> bool {
    let det = determinant(mat3x3f(c0.xyw, c1.xyw, c2.xyw));
    let front = (det > 0.0) != (item.mirrored != 0u);
    return det != 0.0 && (front || field(item.record, kDoubleSided) != 0u);
}

// The clip positions of triangle `triangle` of `item`.
fn clipTriangle(item: Item, transform: Transform, triangle: u32) -> array<vec4f, 3> {
    let record = item.record;
    return array<vec4f, 3>(
        clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 0u))),
        clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 1u))),
        clipPosition(worldPosition(record, transform, vertexIndex(record, triangle, 2u))));
}

// Sizes and snaps triangle `triangle` of `item`. Triangles that cross the near or far plane, or
// span more than the workgroup path takes, are routed to be listed whole (kRouteWhole).
fn prepareTriangle(item: Item, transform: Transform, triangle: u32) -> RasterTriangle {
    var t: RasterTriangle;
    t.route = kRouteNone;
    let c = clipTriangle(item, transform, triangle);
    let c0 = c[0];
    let c1 = c[1];
    let c2 = c[2];
    let xs = vec3f(c0.x, c1.x, c2.x);
    let ys = vec3f(c0.y, c1.y, c2.y);
    let zs = vec3f(c0.z, c1.z, c2.z);
    let ws = vec3f(c0.w, c1.w, c2.w);
    // Wholly outside one clip plane: nothing to draw anywhere.
    if (all(xs < -ws) || all(xs > ws) || all(ys < -ws) || all(ys > ws) || all(zs < vec3f(0.0)) ||
        all(zs > ws)) {
        return t;
    }
    if (any(zs < vec3f(0.0)) || any(zs > ws) || any(ws <= vec3f(0.0))) {
        // Crosses the near or far plane: to be clipped. Facing from the homogeneous
        // determinant, which holds on either side of w = 0.
        if (facesTheCamera(c0, c1, c2, item)) {
            t.route = kRouteWhole;
        }
        return t;
    }
    return prepareProjected(item, c0, c1, c2, false);
}

// Sizes and snaps a triangle of `item` in front of the near plane and behind the far one (clip
// positions c0, c1, c2). Unless `clipped` (a piece of a clipped triangle, within the guard
// band), one spanning more than the workgroup path takes is routed to be listed whole.
fn prepareProjected(item: Item, c0: vec4f, c1: vec4f, c2: vec4f, clipped: bool)
    -> RasterTriangle {
    var t: RasterTriangle;
    t.route = kRouteNone;
    let record = item.record;
    let p0 = windowPosition(c0);
    let p1 = windowPosition(c1);
    let p2 = windowPosition(c2);
    let low = min(p0.xy, min(p1.xy, p2.xy));
    let high = max(p0.xy, max(p1.xy, p2.xy));
    let span = max(high.x - low.x, high.y - low.y);
    if (!clipped && span > max(params.maxComputePixels, params.maxWorkgroupPixels)) {
        if (facesTheCamera(c0, c1, c2, item)) {
            t.route = kRouteWhole;
        }
        return t;
    }
    // Pixels whose centres may be covered (a pixel more each way: snapping moves vertices),
    // inside the viewport. With several samples, anywhere from 1/16 to 15/16 of a pixel in:
    // those whose squares the bounds touch and one more on the low side.
    let viewMin = vec2i(i32(params.viewportX), i32(params.viewportY));
    let viewMax = viewMin + vec2i(i32(params.viewportWidth), i32(params.viewportHeight)) - 1;
    if (params.samples == 1u) {
        t.first = max(vec2i(floor(low - 0.5)), viewMin);
        t.last = min(vec2i(ceil(high - 0.5)), viewMax);
    } else {
        t.first = max(vec2i(floor(low - 1.0)), viewMin);
        t.last = min(vec2i(floor(high)), viewMax);
    }
    if (any(t.last < t.first)) {
        return t;
    }
    t.nearest = min(p0.z, min(p1.z, p2.z));
    // In the second phase, a triangle behind the farthest depth the first phase drew over its
    // pixels would lose every sample's atomic: drawn by neither rasteriser, as a back face.
    if (hiddenByFirstPhase(t.first, t.last, t.nearest)) {
        return t;
    }
    // Fixed point relative to the first pixel, so that products stay within 32 bits up to
    // kNarrowPixels across.
    let origin = vec2f(t.first) * kSubpixels;
    t.v0 = vec2i(round(p0.xy * kSubpixels - origin));
    t.v1 = vec2i(round(p1.xy * kSubpixels - origin));
    t.v2 = vec2i(round(p2.xy * kSubpixels - origin));
    t.wide = span > kNarrowPixels;
    var area: i32;
    if (t.wide) {
        area = wideSign(wideEdge(t.v0, t.v1, t.v2));
    } else {
        area = edge(t.v0, t.v1, t.v2);
    }
    if (area == 0) {
        return t;  // Degenerate once snapped: the hardware draws nothing either.
    }
    // Counter-clockwise in normalised device coordinates (front for glTF) turns clockwise on the
    // y-down screen: area < 0. Mirrored instances face the other way.
    let front = (area < 0) != (item.mirrored != 0u);
    if (!front && field(record, kDoubleSided) == 0u) {
        return t;
    }
    if (area < 0) {
        let swap = t.v1;
        t.v1 = t.v2;
        t.v2 = swap;
    }
    t.bias = triangleBias(t);
    let d1 = p1.xy - p0.xy;
    let d2 = p2.xy - p0.xy;
    let dz = vec2f(p1.z - p0.z, p2.z - p0.z);
    let determinant = d1.x * d2.y - d2.x * d1.y;
    // A sliver degenerate only before snapping: its nearest depth, flat.
    var gradient = vec2f(0.0);
    if (determinant != 0.0) {
        gradient = vec2f(dz.x * d2.y - dz.y * d1.y, dz.y * d1.x - dz.x * d2.x) / determinant;
    }
    let start = select(min(p0.z, min(p1.z, p2.z)), p0.z + dot(gradient, vec2f(t.first) - p0.xy),
                       determinant != 0.0);
    t.depth = vec3f(start, gradient);
    t.route = select(kRouteWorkgroup, kRouteThread, span <= params.maxComputePixels);
    return t;
}

// The triangle's record: what coverListed needs of prepareTriangle (the biases follow from the
// vertices).
fn storeRecord(record: u32, t: RasterTriangle, id: u32) {
    let at = params.workgroupBlocks + record * kRecordEntries;
    workgroupList[at] = vec2u(id, select(0u, 1u, t.wide));
    workgroupList[at + 1u] = bitcast<vec2u>(t.first);
    workgroupList[at + 2u] = bitcast<vec2u>(t.last);
    workgroupList[at + 3u] = bitcast<vec2u>(t.v0);
    workgroupList[at + 4u] = bitcast<vec2u>(t.v1);
    workgroupList[at + 5u] = bitcast<vec2u>(t.v2);
    workgroupList[at + 6u] = bitcast<vec2u>(t.depth.xy);
    workgroupList[at + 7u] = bitcast<vec2u>(vec2f(t.depth.z, t.nearest));
}

// The record's triangle, and its id.
fn loadRecord(record: u32, id: ptr<function, u32>) -> RasterTriangle {
    let at = params.workgroupBlocks + record * kRecordEntries;
    let head = workgroupList[at];
    var t: RasterTriangle;
    t.route = kRouteWorkgroup;
    t.wide = head.y != 0u;
    t.first = bitcast<vec2i>(workgroupList[at + 1u]);
    t.last = bitcast<vec2i>(workgroupList[at + 2u]);
    t.v0 = bitcast<vec2i>(workgroupList[at + 3u]);
    t.v1 = bitcast<vec2i>(workgroupList[at + 4u]);
    t.v2 = bitcast<vec2i>(workgroupList[at + 5u]);
    let depth = bitcast<vec2f>(workgroupList[at + 6u]);
    let rest = bitcast<vec2f>(workgroupList[at + 7u]);
    t.depth = vec3f(depth, rest.x);
    t.nearest = rest.y;
    t.bias = triangleBias(t);
    *id = head.x;
    return t;
}

// Whether, in the second occlusion phase, the first phase's depth pyramid hides something no
// nearer than `nearest` over the pixels [first, last] (of the target: one view, at its origin).
fn hiddenByFirstPhase(first: vec2i, last: vec2i, nearest: f32) -> bool {
    if (counters.secondPhase == 0u) {
        return false;
    }
    let viewport = vec2f(f32(params.viewportWidth), f32(params.viewportHeight));
    let origin = vec2f(f32(params.viewportX), f32(params.viewportY));
    return pyramidHides(depthPyramid, viewport, vec2f(first) - origin, vec2f(last) - origin,
                        nearest);
}

// Writes (depth, id) at each sample of `pixel` that is inside the triangle under the top-left
// rule (its entry of the visibility buffer: pixel * samples + sample).
fn coverPixel(t: RasterTriangle, id: u32, pixel: vec2i) {
    let corner = (pixel - t.first) * i32(kSubpixels);
    let index = (u32(pixel.y) * params.targetWidth + u32(pixel.x)) * params.samples;
    for (var sample = 0u; sample < params.samples; sample++) {
        let p = corner + samplePosition(params.samples, sample);
        var inside: bool;
        if (t.wide) {
            inside = wideInside(t.v1, t.v2, p, t.bias.x) && wideInside(t.v2, t.v0, p, t.bias.y) &&
                     wideInside(t.v0, t.v1, p, t.bias.z);
        } else {
            inside = edge(t.v1, t.v2, p) + t.bias.x >= 0 && edge(t.v2, t.v0, p) + t.bias.y >= 0 &&
                     edge(t.v0, t.v1, p) + t.bias.z >= 0;
        }
        if (inside) {
            let at = vec2f(p) / kSubpixels;  // The sample, in pixels from the first pixel.
            let depth = clamp(t.depth.x + dot(t.depth.yz, at), 0.0, 1.0);
            atomicStoreMax(&visibility[index + sample], vec2u(id, ~bitcast<u32>(depth)));
        }
    }
}

// Returns whether the compute raster takes the triangle (front-facing, on screen, not
// degenerate): small ones it covers here, larger ones it lists for workgroupMain.
fn rasterTriangle(id: u32, item: Item, transform: Transform, triangle: u32) -> bool {
    let t = prepareTriangle(item, transform, triangle);
    if (t.route == kRouteWhole) {
        return listWhole(id);
    }
    if (t.route == kRouteWorkgroup) {
        let blocks = (t.last - t.first + kBlockPixels) / kBlockPixels;
        let count = u32(blocks.x * blocks.y);
        let record = atomicAdd(&counters.workgroupRecords, 1u);
        let slot = atomicAdd(&counters.workgroupTriangles, count);
        let capacity = params.workgroupBlocks;
        let listed = slot <= capacity && count <= capacity - slot;
        if (listed && record < params.workgroupRecords) {
            storeRecord(record, t, id);
            for (var block = 0u; block < count; block++) {
                workgroupList[slot + block] = vec2u(record, block);
            }
            return true;
        }
        // The list is full: listed whole instead, and what it reserved stays empty.
        for (var empty = slot; empty < min(slot + count, capacity); empty++) {
            workgroupList[empty] = vec2u(kNoEntry, 0u);
        }
        return listWhole(id);
    }
    if (t.route != kRouteThread) {
        return false;
    }
    for (var y = t.first.y; y <= t.last.y; y++) {
        for (var x = t.first.x; x <= t.last.x; x++) {
            coverPixel(t, id, vec2i(x, y));
        }
    }
    return true;
}

// A cluster whose cone says every triangle faces away from the camera is not culled unless the
// view lies this far (in cosine) inside the cone: the raster snaps vertices to 1/256 pixel,
// which may turn an almost edge-on triangle to face the camera.
const kConeMargin = 0.01;

// Whether every triangle of the cluster faces away from the view's camera, by its cone of
// normals (meshopt_computeMeshletBounds' test), in object space. Whether a triangle faces the
// camera is the sign of dot(its normal, camera - its corner), which moving both into object
// space keeps, mirrored instances included (their winding flips with the matrix and their front
// face with it, as the pipelines flip it). Double-sided materials never cull by facing.
fn clusterFacesAway(cluster: u32, item: Item, world: mat4x4f) -> bool {
    let cutoff = bitcast<f32>(tables[cluster + kClusterConeCutoff]);
    if (!(cutoff < 1.0) || field(item.record, kDoubleSided) != 0u) {
        return false;
    }
    // The inverse of the world matrix's linear part: its rows over the determinant.
    let bc = cross(world[1].xyz, world[2].xyz);
    let ca = cross(world[2].xyz, world[0].xyz);
    let ab = cross(world[0].xyz, world[1].xyz);
    let det = dot(world[0].xyz, bc);
    if (!(abs(det) > 1e-20)) {
        return false;
    }
    var toApex: vec3f;  // From the camera to the cone's apex (orthographic: the view direction).
    if (frame.projection[3][3] != 0.0) {
        let forward = -vec3f(frame.view[0][2], frame.view[1][2], frame.view[2][2]);
        toApex = vec3f(dot(bc, forward), dot(ca, forward), dot(ab, forward)) / det;
    } else {
        let eye = frame.cameraPosition - world[3].xyz;
        let objectEye = vec3f(dot(bc, eye), dot(ca, eye), dot(ab, eye)) / det;
        toApex = vec3At(cluster, kClusterConeApex) - objectEye;
    }
    let distance = length(toApex);
    return distance > 0.0 &&
           dot(toApex / distance, vec3At(cluster, kClusterConeAxis)) >= cutoff + kConeMargin;
}

// Whether a cluster of `item` can be skipped: its sphere outside the frustum, every triangle
// facing away, or (second occlusion phase) its sphere's box behind the depth pyramid.
fn clusterCulled(cluster: u32, item: Item, world: mat4x4f, secondPhase: bool) -> bool {
    let radius = bitcast<f32>(tables[cluster + kClusterRadius]);
    if (culling.clusterCulling == 0u || !(radius < kNeverCulled)) {
        return false;
    }
    let center = vec3At(cluster, kClusterCenter);
    let worldCenter = (world * vec4f(center, 1.0)).xyz;
    if (sphereOutsideFrustum(worldCenter, radius * largestAxisScale(world))) {
        return true;
    }
    if (clusterFacesAway(cluster, item, world)) {
        return true;
    }
    return secondPhase && boxOccluded(center, vec3f(radius), world);
}

struct ClusterDecision {
    take: bool,    // Rasterise its triangles.
    culled: bool,  // Count them as culled (each listed triangle is taken or culled once).
}

// The cluster's index among its item's clusters of every level (record order), counted from the
// item's first: its word of the clusters' visibility and its entry of the scene's unit table.
fn itemCluster(cluster: u32, item: Item) -> u32 {
    return item.clusterWords + (cluster - field(item.record, kLevelClusters)) / kClusterWords;
}

// What the workgroup does with a cluster. With two-phase occlusion, the standard way per
// cluster: phase 1 takes the clusters visible last frame (culling them by frustum and facing
// only) and leaves the others; phase 2, which lists again the items of phase 1, tests each
// cluster against the pyramid too, takes those phase 1 left that show, and keeps every
// cluster's visibility for the next frame.
// The only cluster of its level follows its item through the phases as before clusters (the
// item tests decide; phase 2 does not list phase 1's items with one cluster again).
fn decideCluster(cluster: u32, alone: bool, item: Item, world: mat4x4f, secondPhase: bool)
    -> ClusterDecision {
    if (culling.occlusion == 0u || culling.clusterCulling == 0u || alone) {
        let skip = clusterCulled(cluster, item, world, secondPhase);
        return ClusterDecision(!skip, skip);
    }
    let word = itemCluster(cluster, item);
    let state = counters.clusterVisibility[word];
    if (!secondPhase) {
        if ((state & 1u) == 0u) {
            return ClusterDecision(false, false);  // Left for phase 2.
        }
        counters.clusterVisibility[word] = 3u;
        let skip = clusterCulled(cluster, item, world, false);
        return ClusterDecision(!skip, skip);
    }
    let skip = clusterCulled(cluster, item, world, true);
    counters.clusterVisibility[word] = select(1u, 0u, skip);
    if ((state & 2u) != 0u) {
        return ClusterDecision(false, false);  // Phase 1 took it.
    }
    return ClusterDecision(!skip, skip);
}

// The number a listed unit's ids count it by: its entry of the scene's unit table, the same
// whatever order the cull listed it in (so depth ties go the same way every run), or without
// the table its place in the list.
fn unitId(listed: u32, unit: vec2u, item: Item) -> u32 {
    if (culling.unitListBase == 0u) {
        return listed;
    }
    return itemCluster(unit.y, item);
}

var<workgroup> rasterised: atomic<u32>;
// This phase's first unit, the end of the list, and 1 in the second phase.
var<workgroup> phaseUnits: vec3u;

// Units in batches (visibility_batch.wgsl): far levels of detail make clusters of a few
// triangles, which a workgroup per cluster would leave mostly idle, each cluster's decision
// waiting on memory alone (H100, 1,000,000 objects: the pass 14% faster; the same at 100,000).
@compute @workgroup_size(64)
fn rasterMain(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u,
              @builtin(local_invocation_index) lane: u32) {
    if (lane == 0u) {
        phaseUnits =
            vec3u(counters.firstUnit, atomicLoad(&counters.unitCount), counters.secondPhase);
    }
    let range = workgroupUniformLoad(&phaseUnits);
    let batch = batchSize(max(range.y, range.x) - range.x, groups.x);
    var count = 0u;
    var culled = 0u;  // Triangles of the clusters culled.
    for (var firstUnit = range.x + group.x * batch; firstUnit < range.y;
         firstUnit += groups.x * batch) {
        var kept = 0u;
        if (lane < min(batch, range.y - firstUnit)) {
            let unit = units[culling.unitListBase + firstUnit + lane];
            let item = loadItem(unit.x);
            let trianglesWord = tables[unit.y + kClusterTriangles];
            let triangles = trianglesWord & ~kClusterAlone;
            let alone = (trianglesWord & kClusterAlone) != 0u;
            let decision = decideCluster(unit.y, alone, item, instances[item.slot].world,
                                         range.z != 0u);
            kept = select(0u, triangles, decision.take);
            culled += select(0u, triangles, decision.culled);
        }
        let slots = batchSlots(lane, kept);
        var entry = 0u;
        for (var slot = lane; slot < slots; slot += 64u) {
            entry = batchEntry(slot, entry);
            let unitIndex = firstUnit + entry;
            let unit = units[culling.unitListBase + unitIndex];
            let item = loadItem(unit.x);
            let local = slot - batchStart(entry);
            let id = unitId(unitIndex, unit, item) * kUnitTriangles + local;
            if (rasterTriangle(id, item, instances[item.slot],
                               tables[unit.y + kClusterFirstTriangle] + local)) {
                count++;
            }
        }
        workgroupBarrier();  // Before the next batch's slots replace these.
    }
    // Most of the grid's workgroups find nothing in a light frame: they add nothing, rather than
    // queue thousands of atomics on one counter (H100 city: the pass 0.038 -> 0.036 ms).
    if (count > 0u) {
        atomicAdd(&rasterised, count);
    }
    workgroupBarrier();
    if (lane == 0u) {
        let total = atomicLoad(&rasterised);
        if (total > 0u) {
            atomicAdd(&counters.computeTriangles, total);
        }
    }
    if (culled > 0u) {
        atomicAdd(&counters.culledTriangles, culled);
    }
}

// Blocks listed, then (params.computeTakesAll) this phase's first triangle listed whole and
// their count.
var<workgroup> listed: vec3u;

// One workgroup per listed block: its 64 threads walk the block's pixels in 8x8 tiles. Then
// kWholeParts per triangle listed whole, where the compute raster takes them.
@compute @workgroup_size(64)
fn workgroupMain(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u,
                 @builtin(local_invocation_index) lane: u32) {
    if (lane == 0u) {
        let first = counters.hardwareFirstVertex / 3u;
        let end = min(first + atomicLoad(&counters.hardwareVertices) / 3u,
                      params.hardwareCapacity);
        let whole = select(0u, end - first, params.computeTakesAll != 0u && end > first);
        listed = vec3u(min(atomicLoad(&counters.workgroupTriangles), params.workgroupBlocks),
                       first, whole);
    }
    let count = workgroupUniformLoad(&listed);
    for (var slot = group.x; slot < count.x; slot += groups.x) {
        coverListed(slot, lane);
    }
    for (var slot = group.x; slot < count.z * kWholeParts; slot += groups.x) {
        coverWhole(hardwareList[count.y + slot / kWholeParts], slot % kWholeParts, lane);
    }
}

// Workgroups that share each triangle listed whole, its tiles dealt out among them: a piece as
// large as the screen (a floor through the near plane) is not one workgroup's alone. Each sets
// the triangle up (clips it) on its own: triangles listed whole are few.
const kWholeParts = 16u;

// Part `part` of triangle `id`, listed whole: clipped, and every kWholeParts-th 8x8 tile of each
// piece from the part's covered by the workgroup's 64 threads (the rare path of triangles
// through the near or far plane, over kMaxWorkgroupPixels, or past full lists).
fn coverWhole(id: u32, part: u32, lane: u32) {
    let unit = units[id / kUnitTriangles];
    let item = loadItem(unit.x);
    let c = clipTriangle(item, instances[item.slot], unitTriangle(unit, id));
    let polygon = clipPolygon(c[0], c[1], c[2],
                              vec2f(f32(params.viewportWidth), f32(params.viewportHeight)));
    for (var k = 2u; k < polygon.count; k++) {
        let t = prepareProjected(item, polygon.v[0], polygon.v[k - 1u], polygon.v[k], true);
        if (t.route == kRouteNone) {
            continue;
        }
        coverTiles(t, id, t.first, t.last - t.first + 1, lane, part, kWholeParts);
    }
}

// The pixels of triangle `t` in the `extent` from `origin`, in 8x8 tiles a thread of the
// workgroup per pixel: tiles `first`, first + stride, ... (a block's all, or a share of a
// triangle listed whole).
fn coverTiles(t: RasterTriangle, id: u32, origin: vec2i, extent: vec2i, lane: u32, first: u32,
              stride: u32) {
    let columns = (extent.x + 7) / 8;
    let tiles = columns * ((extent.y + 7) / 8);
    let offset = vec2i(i32(lane % 8u), i32(lane / 8u));
    for (var tile = i32(first); tile < tiles; tile += i32(stride)) {
        let pixel = vec2i(tile % columns, tile / columns) * 8 + offset;
        if (all(pixel < extent)) {
            coverPixel(t, id, origin + pixel);
        }
    }
}

// The listed block at `slot`: its triangle's pixels in that block, in 8x8 tiles, one per thread
// of the workgroup.
fn coverListed(slot: u32, lane: u32) {
    let entry = workgroupList[slot];
    if (entry.x == kNoEntry) {
        return;
    }
    var id: u32;
    let t = loadRecord(entry.x, &id);
    let size = t.last - t.first + 1;
    let blockColumns = (size.x + kBlockPixels - 1) / kBlockPixels;
    let block = vec2i(i32(entry.y) % blockColumns, i32(entry.y) / blockColumns) * kBlockPixels;
    let extent = min(size - block, vec2i(kBlockPixels));
    if (hiddenByFirstPhase(t.first + block, t.first + block + extent - 1, t.nearest)) {
        return;
    }
    coverTiles(t, id, t.first + block, extent, lane, 0u, 1u);
}
