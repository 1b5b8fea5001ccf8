// GPU frustum culling. Every frame, `resetCounts` zeroes the instanceCount of every indirect
// draw, then `cullInstances` bounds each instance where this frame's transforms put it
// (render::CullingBounds: a rigid sphere moved by the instance's world matrix, joint spheres
// moved by the joint matrices, grown by the morph deltas the current weights allow) and, when
// the hull of those spheres meets the frustum, appends the instance to the visible list of
// every draw of its mesh: atomicAdd on that draw's instanceCount gives the slot. Indirect
// arguments keep firstInstance 0 (see mesh.wgsl). It also counts the triangles it lets through
// in the word after the last argument record (render::GpuCuller::drawnTrianglesOffset; no
// binding of its own: the pass already uses the 8 storage buffers of the default limits),
// summed per workgroup first so that a million instances do not all add to one word.

struct Frustum {
    planes: array<vec4f, 6>,  // xyz: inward normal, w: distance; visible when dot >= -radius.
}

// One instance slot (render::SlotBounds).
struct SlotBounds {
    rigidSphere: vec4f,  // Object space; radius < 0: every primitive is skinned.
    firstJointSphere: u32,
    jointCount: u32,
    jointOffset: u32,
    firstMorphExtent: u32,  // In floats.
    morphCount: u32,
    weightOffset: u32,
    firstDraw: u32,  // The culled draws of the slot's mesh, in `draws`.
    drawCount: u32,
}

struct Transform {
    world: mat4x4f,
    normal: mat4x4f,
}

// Per draw: where its visible list starts (in entries).
struct Draw {
    visibleBase: u32,
    argumentsOffset: u32,  // In u32 words; instanceCount is the next word.
    triangles: u32,        // Per instance.
}

@group(0) @binding(0) var<uniform> frustum: Frustum;
@group(0) @binding(1) var<storage, read> slots: array<SlotBounds>;
@group(0) @binding(2) var<storage, read> instances: array<Transform>;  // Per slot.
@group(0) @binding(3) var<storage, read> shapes: array<vec4f>;
@group(0) @binding(4) var<storage, read> draws: array<Draw>;
@group(0) @binding(5) var<storage, read_write> indirectArguments: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> visibleInstances: array<u32>;
@group(0) @binding(7) var<storage, read> joints: array<Transform>;
@group(0) @binding(8) var<storage, read> morphWeights: array<f32>;

var<workgroup> workgroupTriangles: atomic<u32>;  // Zero at the start of each workgroup.

// The frame's drawn triangles (wraps past 2^32, far beyond the benchmark scenes): the last
// word of indirectArguments.
fn drawnTrianglesWord() -> u32 {
    return arrayLength(&indirectArguments) - 1u;
}

override kWorkgroupSize: u32 = 64;

@compute @workgroup_size(kWorkgroupSize)
fn resetCounts(@builtin(global_invocation_id) id: vec3u) {
    if (id.x == 0u) {
        atomicStore(&indirectArguments[drawnTrianglesWord()], 0u);
    }
    if (id.x >= arrayLength(&draws)) {
        return;
    }
    atomicStore(&indirectArguments[draws[id.x].argumentsOffset + 1u], 0u);
}

fn largestAxisScale(m: mat4x4f) -> f32 {
    return sqrt(max(max(dot(m[0].xyz, m[0].xyz), dot(m[1].xyz, m[1].xyz)),
                    dot(m[2].xyz, m[2].xyz)));
}

// Per plane, how far inside the farthest sphere so far reaches (negative: all outside).
struct Reach {
    planes: array<f32, 6>,
}

fn extend(reach: ptr<function, Reach>, transform: mat4x4f, sphere: vec4f, growth: f32) {
    let center = (transform * vec4f(sphere.xyz, 1.0)).xyz;
    let radius = (sphere.w + growth) * largestAxisScale(transform);
    for (var i = 0u; i < 6u; i++) {
        let plane = frustum.planes[i];
        (*reach).planes[i] = max((*reach).planes[i], dot(plane.xyz, center) + plane.w + radius);
    }
}

fn isVisible(slot: u32) -> bool {
    let bounds = slots[slot];
    var growth = 0.0;
    for (var t = 0u; t < bounds.morphCount; t++) {
        let extent = bounds.firstMorphExtent + t;
        growth += abs(morphWeights[bounds.weightOffset + t]) * shapes[extent / 4u][extent % 4u];
    }
    var reach: Reach;
    for (var i = 0u; i < 6u; i++) {
        reach.planes[i] = -3.4e38;
    }
    if (bounds.rigidSphere.w >= 0.0) {
        extend(&reach, instances[slot].world, bounds.rigidSphere, growth);
    }
    for (var j = 0u; j < bounds.jointCount; j++) {
        let sphere = shapes[bounds.firstJointSphere + j];
        if (sphere.w >= 0.0) {
            extend(&reach, joints[bounds.jointOffset + j].world, sphere, growth);
        }
    }
    for (var i = 0u; i < 6u; i++) {
        if (reach.planes[i] < 0.0) {
            return false;
        }
    }
    return true;
}

@compute @workgroup_size(kWorkgroupSize)
fn cullInstances(@builtin(global_invocation_id) id: vec3u,
                 @builtin(local_invocation_index) local: u32) {
    let slot = id.x;
    // No early return: the barrier below needs every invocation of the workgroup.
    if (slot < arrayLength(&slots) && isVisible(slot)) {
        let bounds = slots[slot];
        var triangles = 0u;
        for (var i = 0u; i < bounds.drawCount; i++) {
            let draw = draws[bounds.firstDraw + i];
            let index = atomicAdd(&indirectArguments[draw.argumentsOffset + 1u], 1u);
            visibleInstances[draw.visibleBase + index] = slot;
            triangles += draw.triangles;
        }
        atomicAdd(&workgroupTriangles, triangles);
    }
    workgroupBarrier();
    if (local == 0u) {
        let triangles = atomicLoad(&workgroupTriangles);
        if (triangles > 0u) {
            atomicAdd(&indirectArguments[drawnTrianglesWord()], triangles);
        }
    }
}
