// GPU culling with levels of detail and two-phase occlusion culling (render::GpuCuller).
//
// Each instance slot is bounded where this frame's transforms put it (render::CullingBounds: a
// rigid sphere moved by the instance's world matrix, joint spheres moved by the joint matrices,
// grown by the morph deltas the current weights allow). A visible instance is appended to the
// visible list of one indirect draw per primitive of its mesh: the draw of the level of detail
// chosen for it (the coarsest whose object-space error, projected, stays under the threshold),
// atomicAdd on that draw's instanceCount giving the slot. Indirect arguments keep firstInstance 0
// (see mesh.wgsl).
//
// Every draw has two argument records and two visible lists, one per phase. A frame of one view
// with occlusion culling runs:
//   resetCounts; cullFirstPhase: instances in the frustum that were visible last frame -> phase 1;
//   (phase 1 is drawn; depth_pyramid.wgsl reduces its depth)
//   cullSecondPhase: every instance in the frustum is tested against the pyramid; the visible ones
//   not drawn in phase 1 -> phase 2; the result is remembered for the next frame.
// Without occlusion culling, cullFirstPhase takes every instance in the frustum and phase 2
// stays empty.

#include "culling_view.wgsl"
#include "pyramid_occlusion.wgsl"

// One instance slot (render::SlotBounds).
struct SlotBounds {
    rigidSphere: vec4f,  // Object space; radius < 0: every primitive is skinned.
    firstJointSphere: u32,
    jointCount: u32,
    jointOffset: u32,
    firstMorphExtent: u32,  // In floats.
    morphCount: u32,
    weightOffset: u32,
    firstDraw: u32,  // The culled primitives of the slot's mesh, in `primitives`.
    drawCount: u32,
}

struct Transform {
    world: mat4x4f,
    normal: mat4x4f,
}

// `records` holds, per culled primitive, (firstLevel, levelCount, 0, 0): its levels of detail,
// finer to coarser, contiguous from `levelBase + firstLevel`; and per level, one indirect draw of
// the primitive at that level (its phase 1 records; phase 2's follow at the phase strides):
struct Level {
    visibleBase: u32,      // In entries.
    argumentsOffset: u32,  // In u32 words; instanceCount is the next word.
    triangles: u32,        // Per instance.
    error: f32,            // Object-space simplification error (0 for the mesh as loaded).
}

fn levelAt(index: u32) -> Level {
    let record = records[culling.levelBase + index];
    return Level(record.x, record.y, record.z, bitcast<f32>(record.w));
}

@group(0) @binding(0) var<uniform> culling: Culling;
@group(0) @binding(1) var<storage, read> slots: array<SlotBounds>;
@group(0) @binding(2) var<storage, read> instances: array<Transform>;  // Per slot.
@group(0) @binding(3) var<storage, read> shapes: array<vec4f>;
@group(0) @binding(4) var<storage, read> records: array<vec4u>;
@group(0) @binding(5) var<storage, read_write> indirectArguments: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> visibleInstances: array<u32>;
@group(0) @binding(7) var<storage, read> joints: array<Transform>;
@group(0) @binding(8) var<storage, read> morphWeights: array<f32>;

@group(1) @binding(0) var depthPyramid: texture_2d<f32>;  // cullSecondPhase only.

override kWorkgroupSize: u32 = 64;

// The triangles a workgroup appended, added to the frame's count once per workgroup rather than
// once per instance (a million atomics on one word serialise).
var<workgroup> trianglesAppended: atomic<u32>;

@compute @workgroup_size(kWorkgroupSize)
fn resetCounts(@builtin(global_invocation_id) id: vec3u) {
    if (id.x == 0u) {
        atomicStore(&indirectArguments[culling.trianglesDrawnWord], 0u);
    }
    if (culling.levelBase + id.x >= arrayLength(&records)) {
        return;
    }
    let arguments = levelAt(id.x).argumentsOffset + 1u;
    atomicStore(&indirectArguments[arguments], 0u);
    atomicStore(&indirectArguments[arguments + culling.phaseArguments], 0u);
}

// Where an instance is this frame: per frustum plane, how far inside the farthest of its spheres
// reaches (negative: all outside), and the world-space box around the spheres.
struct InstanceBounds {
    reach: array<f32, 6>,
    boxMin: vec3f,
    boxMax: vec3f,
    scale: f32,  // The largest axis scale of the transforms that moved the spheres.
}

fn extend(bounds: ptr<function, InstanceBounds>, transform: mat4x4f, sphere: vec4f, growth: f32) {
    let scale = largestAxisScale(transform);
    let center = (transform * vec4f(sphere.xyz, 1.0)).xyz;
    let radius = (sphere.w + growth) * scale;
    for (var i = 0u; i < 6u; i++) {
        (*bounds).reach[i] = max((*bounds).reach[i], sphereReach(i, center, radius));
    }
    (*bounds).boxMin = min((*bounds).boxMin, center - vec3f(radius));
    (*bounds).boxMax = max((*bounds).boxMax, center + vec3f(radius));
    (*bounds).scale = max((*bounds).scale, scale);
}

fn boundsOf(slot: u32) -> InstanceBounds {
    let bounds = slots[slot];
    var growth = 0.0;
    for (var t = 0u; t < bounds.morphCount; t++) {
        let extent = bounds.firstMorphExtent + t;
        growth += abs(morphWeights[bounds.weightOffset + t]) * shapes[extent / 4u][extent % 4u];
    }
    var result: InstanceBounds;
    for (var i = 0u; i < 6u; i++) {
        result.reach[i] = -3.4e38;
    }
    result.boxMin = vec3f(3.4e38);
    result.boxMax = vec3f(-3.4e38);
    result.scale = 0.0;
    if (bounds.rigidSphere.w >= 0.0) {
        extend(&result, instances[slot].world, bounds.rigidSphere, growth);
    }
    for (var j = 0u; j < bounds.jointCount; j++) {
        let sphere = shapes[bounds.firstJointSphere + j];
        if (sphere.w >= 0.0) {
            extend(&result, joints[bounds.jointOffset + j].world, sphere, growth);
        }
    }
    return result;
}

fn inFrustum(bounds: InstanceBounds) -> bool {
    for (var i = 0u; i < 6u; i++) {
        if (bounds.reach[i] < 0.0) {
            return false;
        }
    }
    return true;
}

// Pixels that one object-space unit of the instance covers at its nearest point (0: levels of
// detail off); the same for every primitive of the instance.
fn lodPixelsPerUnit(bounds: InstanceBounds) -> f32 {
    return lodPixelsPerUnitAt(bounds.boxMin, bounds.boxMax, bounds.scale);
}

// The coarsest level whose error, projected at `pixelsPerUnit`, stays under the threshold
// (levels are ordered finer to coarser, errors growing).
fn chooseLevel(primitive: vec4u, pixelsPerUnit: f32) -> u32 {
    let firstLevel = primitive.x;
    let levelCount = primitive.y;
    if (levelCount <= 1u || pixelsPerUnit <= 0.0) {
        return firstLevel;
    }
    var chosen = firstLevel;
    for (var level = 1u; level < levelCount; level++) {
        let candidate = firstLevel + level;
        if (levelAt(candidate).error * pixelsPerUnit > culling.lodThresholdPixels) {
            break;
        }
        chosen = candidate;
    }
    return chosen;
}

// Appends the slot to the draws of its primitives' chosen levels; returns the triangles added.
fn append(slot: u32, bounds: InstanceBounds, phase: u32) -> u32 {
    let record = slots[slot];
    let pixelsPerUnit = lodPixelsPerUnit(bounds);
    var triangles = 0u;
    for (var i = 0u; i < record.drawCount; i++) {
        let level = levelAt(chooseLevel(records[record.firstDraw + i], pixelsPerUnit));
        let index = atomicAdd(
            &indirectArguments[level.argumentsOffset + 1u + phase * culling.phaseArguments], 1u);
        visibleInstances[level.visibleBase + phase * culling.phaseVisible + index] = slot;
        triangles += level.triangles;
    }
    return triangles;
}

fn wasVisibleLastFrame(slot: u32) -> bool {
    return visibleInstances[culling.visibilityBase + slot] != 0u;
}

// Ends a cull: the workgroup's triangles join the frame's count. Every invocation gets here (no
// early return), as the barrier requires.
fn countTriangles(local: u32, triangles: u32) {
    if (triangles > 0u) {
        atomicAdd(&trianglesAppended, triangles);
    }
    workgroupBarrier();
    if (local == 0u) {
        let total = atomicLoad(&trianglesAppended);
        if (total > 0u) {
            atomicAdd(&indirectArguments[culling.trianglesDrawnWord], total);
        }
    }
}

@compute @workgroup_size(kWorkgroupSize)
fn cullFirstPhase(@builtin(global_invocation_id) id: vec3u,
                  @builtin(local_invocation_index) local: u32) {
    let slot = id.x;
    var triangles = 0u;
    if (slot < arrayLength(&slots) && (culling.occlusion == 0u || wasVisibleLastFrame(slot))) {
        let bounds = boundsOf(slot);
        if (inFrustum(bounds)) {
            triangles = append(slot, bounds, 0u);
        }
    }
    countTriangles(local, triangles);
}

// Whether the pyramid proves the box hidden: its nearest depth lies behind the farthest depth
// drawn anywhere over the pixels it covers.
fn isOccluded(bounds: InstanceBounds) -> bool {
    var low = vec2f(3.4e38);
    var high = vec2f(-3.4e38);
    var nearestDepth = 1.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let point = select(bounds.boxMin, bounds.boxMax,
                           vec3<bool>((corner & 1u) != 0u, (corner & 2u) != 0u,
                                      (corner & 4u) != 0u));
        let clip = culling.viewProjection * vec4f(point, 1.0);
        if (clip.w <= 1e-6 || clip.z < 0.0) {
            return false;  // The box reaches the near plane: it may cover the whole view.
        }
        let ndc = clip.xyz / clip.w;
        let pixel = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * culling.viewport;
        low = min(low, pixel);
        high = max(high, pixel);
        nearestDepth = min(nearestDepth, ndc.z);
    }
    return pyramidHides(depthPyramid, culling.viewport, low, high, nearestDepth);
}

@compute @workgroup_size(kWorkgroupSize)
fn cullSecondPhase(@builtin(global_invocation_id) id: vec3u,
                   @builtin(local_invocation_index) local: u32) {
    let slot = id.x;
    var triangles = 0u;
    if (slot < arrayLength(&slots)) {
        let bounds = boundsOf(slot);
        let visible = inFrustum(bounds) && !isOccluded(bounds);
        if (visible && !wasVisibleLastFrame(slot)) {
            triangles = append(slot, bounds, 1u);
        }
        visibleInstances[culling.visibilityBase + slot] = select(0u, 1u, visible);
    }
    countTriangles(local, triangles);
}
