// The visibility strategy's culling, for one view: one thread per item (instance x primitive)
// lists the units (256 triangles each) of the item's chosen level of detail for the raster
// passes (visibility_raster.wgsl). With two-phase occlusion culling (frames of one view):
//   cullFirstPhase    items in the frustum that were visible last frame;
//   (rasterised; depth_pyramid.wgsl reduces the visibility buffer's depth)
//   beginSecondPhase  the raster passes will take only what follows;
//   cullSecondPhase   every item in the frustum is tested against the pyramid; the visible ones
//                     that phase 1 did not list are listed now, and each item's visibility is
//                     kept for the next frame.
// Without it, cullFirstPhase lists every item in the frustum. Levels of detail are chosen as
// culling.wgsl chooses them (same sphere, same metric, same thresholds: render/LodSelection.h).
#include "frame.wgsl"
#include "visibility_geometry.wgsl"
#include "visibility_levels.wgsl"
#include "visibility_counters.wgsl"
#include "pyramid_occlusion.wgsl"

// VisibilityStrategy.cpp's CullUniform: one per frame.
struct Culling {
    planes: array<vec4f, 6>,  // xyz: inward unit normal, w: distance.
    viewProjection: mat4x4f,
    lodViewCount: u32,
    lodPixelsPerUnit: f32,  // 0: levels of detail off.
    lodThresholdPixels: f32,
    orthographic: u32,
    occlusion: u32,  // 1: two phases; cullFirstPhase reads last frame's visibility.
    frustumTest: u32,  // 0 in multi-view frames, whose views each frame the whole scene.
    lodDistanceSlack: f32,
    padding: u32,
    lodViews: array<vec4f, 16>,
}

@group(1) @binding(4) var<storage, read_write> units: array<vec2u>;
@group(1) @binding(5) var<storage, read_write> counters: Counters;
@group(1) @binding(10) var<uniform> culling: Culling;
// Per item: 1 when it was visible in the last two-phase frame.
@group(1) @binding(11) var<storage, read_write> itemVisibility: array<u32>;
@group(1) @binding(12) var depthPyramid: texture_2d<f32>;  // cullSecondPhase only.

const kMaxGroups = 65535u;

fn largestAxisScale(m: mat4x4f) -> f32 {
    return sqrt(max(max(dot(m[0].xyz, m[0].xyz), dot(m[1].xyz, m[1].xyz)),
                    dot(m[2].xyz, m[2].xyz)));
}

// Whether the item's bounds lie wholly outside one of the frustum's planes.
fn outsideFrustum(item: Item, world: mat4x4f) -> bool {
    if (culling.frustumTest == 0u) {
        return false;
    }
    let center = (world * vec4f(vec3At(item.record, kBoundsCenter), 1.0)).xyz;
    let scale = max(length(world[0].xyz), max(length(world[1].xyz), length(world[2].xyz)));
    let radius = length(vec3At(item.record, kBoundsExtent)) * scale;
    for (var i = 0u; i < 6u; i++) {
        let plane = culling.planes[i];
        if (dot(plane.xyz, center) + plane.w < -radius) {
            return true;
        }
    }
    return false;
}

// culling.wgsl's lodPixelsPerUnit and chooseLevel for the item's mesh sphere, in the same order
// (so the same rounding): the coarsest level whose projected error stays under the threshold.
fn chooseLevel(item: Item, world: mat4x4f) -> u32 {
    let levelCount = field(item.record, kLevelCount) + 1u;
    if (levelCount <= 1u || culling.lodPixelsPerUnit <= 0.0) {
        return 0u;
    }
    let sphere = bitcast<vec4f>(vec4u(tables[item.record + kMeshSphere],
                                      tables[item.record + kMeshSphere + 1u],
                                      tables[item.record + kMeshSphere + 2u],
                                      tables[item.record + kMeshSphere + 3u]));
    let scale = largestAxisScale(world);
    let center = (world * vec4f(sphere.xyz, 1.0)).xyz;
    let radius = sphere.w * scale;
    let boxMin = center - vec3f(radius);
    let boxMax = center + vec3f(radius);
    var pixelsPerUnit = culling.lodPixelsPerUnit * scale;
    if (culling.orthographic == 0u) {
        var nearest = 3.4e38;
        for (var view = 0u; view < culling.lodViewCount; view++) {
            let position = culling.lodViews[view].xyz;
            nearest = min(nearest, distance(clamp(position, boxMin, boxMax), position));
        }
        pixelsPerUnit /= max(nearest - culling.lodDistanceSlack, 1e-6);
    }
    var chosen = 0u;
    for (var level = 1u; level < levelCount; level++) {
        if (levelError(item.record, level) * pixelsPerUnit > culling.lodThresholdPixels) {
            break;
        }
        chosen = level;
    }
    return chosen;
}

// Lists the units of the item's chosen level; returns its triangles.
fn append(index: u32, item: Item, world: mat4x4f) -> u32 {
    let range = levelRange(item.record, chooseLevel(item, world));
    let count = (range.count + kUnitTriangles - 1u) / kUnitTriangles;
    let first = atomicAdd(&counters.unitCount, count);
    for (var unit = 0u; unit < count; unit++) {
        units[first + unit] = vec2u(index, range.first + unit * kUnitTriangles);
    }
    return range.count;
}

// The triangles a workgroup listed, added to the view's count once per workgroup.
var<workgroup> listedInGroup: atomic<u32>;

// Ends a cull. Every invocation gets here (no early return), as the barrier requires.
fn countListed(lane: u32, triangles: u32) {
    if (triangles > 0u) {
        atomicAdd(&listedInGroup, triangles);
    }
    workgroupBarrier();
    if (lane == 0u) {
        let total = atomicLoad(&listedInGroup);
        if (total > 0u) {
            atomicAdd(&counters.listedTriangles, total);
        }
    }
}

fn itemIndex(group: vec3u, lane: u32) -> u32 {
    return (group.y * kMaxGroups + group.x) * 64u + lane;
}

@compute @workgroup_size(64)
fn cullFirstPhase(@builtin(workgroup_id) group: vec3u,
                  @builtin(local_invocation_index) lane: u32) {
    let index = itemIndex(group, lane);
    var triangles = 0u;
    if (index < params.itemCount && (culling.occlusion == 0u || itemVisibility[index] != 0u)) {
        let item = loadItem(index);
        let world = instances[item.slot].world;
        if (!outsideFrustum(item, world)) {
            triangles = append(index, item, world);
        }
    }
    countListed(lane, triangles);
}

@compute @workgroup_size(1)
fn beginSecondPhase() {
    counters.firstUnit = atomicLoad(&counters.unitCount);
    counters.hardwareFirstVertex += atomicLoad(&counters.hardwareVertices);
    atomicStore(&counters.hardwareVertices, 0u);
    atomicStore(&counters.workgroupTriangles, 0u);
}

// Whether the pyramid proves the item hidden: the nearest depth of its box (the primitive's
// bounds, moved by the world matrix) lies behind the farthest depth drawn anywhere over the
// pixels the box covers (as culling.wgsl's isOccluded, for the box's eight corners).
fn isOccluded(item: Item, world: mat4x4f) -> bool {
    let center = vec3At(item.record, kBoundsCenter);
    let extent = vec3At(item.record, kBoundsExtent);
    if (any(extent >= vec3f(1e29))) {
        return false;  // No bounds: never culled.
    }
    let viewport = vec2f(f32(params.viewportWidth), f32(params.viewportHeight));
    var low = vec2f(3.4e38);
    var high = vec2f(-3.4e38);
    var nearestDepth = 1.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let side = select(vec3f(-1.0), vec3f(1.0),
                          vec3<bool>((corner & 1u) != 0u, (corner & 2u) != 0u,
                                     (corner & 4u) != 0u));
        let clip = culling.viewProjection * (world * vec4f(center + side * extent, 1.0));
        if (clip.w <= 1e-6 || clip.z < 0.0) {
            return false;  // The box reaches the near plane: it may cover the whole view.
        }
        let ndc = clip.xyz / clip.w;
        let pixel = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * viewport;
        low = min(low, pixel);
        high = max(high, pixel);
        nearestDepth = min(nearestDepth, ndc.z);
    }
    return pyramidHides(depthPyramid, viewport, low, high, nearestDepth);
}

@compute @workgroup_size(64)
fn cullSecondPhase(@builtin(workgroup_id) group: vec3u,
                   @builtin(local_invocation_index) lane: u32) {
    let index = itemIndex(group, lane);
    var triangles = 0u;
    if (index < params.itemCount) {
        let item = loadItem(index);
        let world = instances[item.slot].world;
        let visible = !outsideFrustum(item, world) && !isOccluded(item, world);
        if (visible && itemVisibility[index] == 0u) {
            triangles = append(index, item, world);
        }
        itemVisibility[index] = select(0u, 1u, visible);
    }
    countListed(lane, triangles);
}
