// The visibility strategy's culling, for one view: one thread per item (instance x primitive)
// lists the units (its clusters, up to 256 triangles each) of the item's chosen level of detail
// for the raster passes (visibility_raster.wgsl), which cull each cluster on its own. With
// two-phase occlusion culling (frames of one view):
//   cullFirstPhase    items in the frustum that were visible last frame;
//   (rasterised; depth_pyramid.wgsl reduces the visibility buffer's depth)
//   beginSecondPhase  the raster passes will take only what follows;
//   cullSecondPhase   every item in the frustum is tested against the pyramid; the visible ones
//                     that phase 1 did not list are listed now, and each item's visibility is
//                     kept for the next frame. With cluster culling, those phase 1 listed are
//                     listed again when their level has several clusters, for the clusters it
//                     left (visibility_raster.wgsl).
// Without it, cullFirstPhase lists every item in the frustum. Levels of detail are chosen as
// culling.wgsl chooses them (same sphere, same metric, same thresholds:
// render/culling/LodSelection.h).
#include "frame.wgsl"
#include "visibility_geometry.wgsl"
#include "visibility_levels.wgsl"
#include "visibility_counters.wgsl"
#include "pyramid_occlusion.wgsl"
#include "visibility_culling.wgsl"

@group(1) @binding(4) var<storage, read_write> units: array<vec2u>;
@group(1) @binding(5) var<storage, read_write> counters: Counters;
// Per item: 1 when it was visible in the last two-phase frame.
@group(1) @binding(11) var<storage, read_write> itemVisibility: array<u32>;
// Per item, the world-space sphere of its bounds (xyz centre, w radius), written by
// worldSphereMain once the transforms stop changing (VisibilityStrategy): while they hold
// (Culling.worldSpheres), a frustum test reads these 16 bytes, not the item and its 64-byte
// matrix. On the H100 that read was most of the second phase's cull of a million items.
@group(1) @binding(13) var<storage, read_write> worldSpheres: array<vec4f>;

const kMaxGroups = 65535u;

// The sphere around the item's bounds (its primitive's box), moved by `world`.
fn boundingSphere(item: Item, world: mat4x4f) -> vec4f {
    let center = (world * vec4f(vec3At(item.record, kBoundsCenter), 1.0)).xyz;
    let scale = max(length(world[0].xyz), max(length(world[1].xyz), length(world[2].xyz)));
    return vec4f(center, length(vec3At(item.record, kBoundsExtent)) * scale);
}

// Whether item `index`'s bounds lie wholly outside one of the frustum's planes.
fn outsideFrustum(index: u32) -> bool {
    if (culling.frustumTest == 0u) {
        return false;
    }
    var sphere: vec4f;
    if (culling.worldSpheres != 0u) {
        sphere = worldSpheres[index];
    } else {
        let item = loadItem(index);
        sphere = boundingSphere(item, instances[item.slot].world);
    }
    return sphereOutsideFrustum(sphere.xyz, sphere.w);
}

// culling.wgsl's chooseLevel for the item's mesh sphere, by the same lodPixelsPerUnitAt
// (culling_view.wgsl): the coarsest level whose projected error stays under the threshold.
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
    let pixelsPerUnit = lodPixelsPerUnitAt(boxMin, boxMax, scale);
    var chosen = 0u;
    for (var level = 1u; level < levelCount; level++) {
        if (levelError(item.record, level) * pixelsPerUnit > culling.lodThresholdPixels) {
            break;
        }
        chosen = level;
    }
    return chosen;
}

// Lists the clusters of the item's chosen level as units; returns the level's triangles.
fn append(index: u32, item: Item, world: mat4x4f) -> u32 {
    let level = chooseLevel(item, world);
    let clusters = levelClusters(item.record, level);
    let first = atomicAdd(&counters.unitCount, clusters.count);
    for (var unit = 0u; unit < clusters.count; unit++) {
        units[culling.unitListBase + first + unit] =
            vec2u(index, clusters.first + unit * kClusterWords);
    }
    return levelRange(item.record, level).count;
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
fn worldSphereMain(@builtin(workgroup_id) group: vec3u,
                   @builtin(local_invocation_index) lane: u32) {
    let index = itemIndex(group, lane);
    if (index < params.itemCount) {
        let item = loadItem(index);
        worldSpheres[index] = boundingSphere(item, instances[item.slot].world);
    }
}

@compute @workgroup_size(64)
fn cullFirstPhase(@builtin(workgroup_id) group: vec3u,
                  @builtin(local_invocation_index) lane: u32) {
    let index = itemIndex(group, lane);
    var triangles = 0u;
    if (index < params.itemCount && (culling.occlusion == 0u || itemVisibility[index] != 0u) &&
        !outsideFrustum(index)) {
        let item = loadItem(index);
        triangles = append(index, item, instances[item.slot].world);
    }
    countListed(lane, triangles);
}

@compute @workgroup_size(1)
fn beginSecondPhase() {
    counters.firstUnit = atomicLoad(&counters.unitCount);
    counters.secondPhase = 1u;
    counters.hardwareFirstVertex += atomicLoad(&counters.hardwareVertices);
    atomicStore(&counters.hardwareVertices, 0u);
    atomicStore(&counters.workgroupTriangles, 0u);
    atomicStore(&counters.workgroupRecords, 0u);
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
    return boxOccluded(center, extent, world);
}

@compute @workgroup_size(64)
fn cullSecondPhase(@builtin(workgroup_id) group: vec3u,
                   @builtin(local_invocation_index) lane: u32) {
    let index = itemIndex(group, lane);
    var triangles = 0u;
    if (index < params.itemCount) {
        var visible = false;
        if (!outsideFrustum(index)) {
            let item = loadItem(index);
            let world = instances[item.slot].world;
            let listedFirst = itemVisibility[index] != 0u;  // By cullFirstPhase.
            visible = !isOccluded(item, world);
            if (visible && !listedFirst) {
                triangles = append(index, item, world);
            } else if (listedFirst && culling.clusterCulling != 0u &&
                       levelClusters(item.record, chooseLevel(item, world)).count > 1u) {
                // Listed again (its triangles counted once): the raster tests the clusters that
                // phase 1 left for this one, and keeps each one's visibility for the next frame.
                _ = append(index, item, world);
            }
        }
        itemVisibility[index] = select(0u, 1u, visible);
    }
    countListed(lane, triangles);
}
