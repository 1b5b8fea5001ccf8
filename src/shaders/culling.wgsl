// GPU frustum culling. Every frame, `resetCounts` zeroes the instanceCount of every indirect
// draw, then `cullInstances` tests each instance's bounding sphere against the frustum and, when
// visible, appends it to the visible list of every draw of its mesh: atomicAdd on that draw's
// instanceCount gives the slot. Indirect arguments keep firstInstance 0 (see mesh.wgsl).

struct Frustum {
    planes: array<vec4f, 6>,  // xyz: inward normal, w: distance; visible when dot >= -radius.
}

// The draws of one mesh's instance range (regular or mirrored instances of one mesh).
struct InstanceRange {
    firstDraw: u32,
    drawCount: u32,
}

// Per draw: where its visible list starts (in entries).
struct Draw {
    visibleBase: u32,
    argumentsOffset: u32,  // In u32 words; instanceCount is the next word.
}

@group(0) @binding(0) var<uniform> frustum: Frustum;
@group(0) @binding(1) var<storage, read> spheres: array<vec4f>;          // Per instance slot.
@group(0) @binding(2) var<storage, read> rangeOfSlot: array<u32>;        // Per instance slot.
@group(0) @binding(3) var<storage, read> ranges: array<InstanceRange>;
@group(0) @binding(4) var<storage, read> draws: array<Draw>;
@group(0) @binding(5) var<storage, read_write> indirectArguments: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> visibleInstances: array<u32>;

override kWorkgroupSize: u32 = 64;

@compute @workgroup_size(kWorkgroupSize)
fn resetCounts(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= arrayLength(&draws)) {
        return;
    }
    atomicStore(&indirectArguments[draws[id.x].argumentsOffset + 1u], 0u);
}

fn isVisible(sphere: vec4f) -> bool {
    for (var i = 0u; i < 6u; i++) {
        let plane = frustum.planes[i];
        if (dot(plane.xyz, sphere.xyz) + plane.w < -sphere.w) {
            return false;
        }
    }
    return true;
}

@compute @workgroup_size(kWorkgroupSize)
fn cullInstances(@builtin(global_invocation_id) id: vec3u) {
    let slot = id.x;
    if (slot >= arrayLength(&rangeOfSlot) || !isVisible(spheres[slot])) {
        return;
    }
    let range = ranges[rangeOfSlot[slot]];
    for (var i = 0u; i < range.drawCount; i++) {
        let draw = draws[range.firstDraw + i];
        let index = atomicAdd(&indirectArguments[draw.argumentsOffset + 1u], 1u);
        visibleInstances[draw.visibleBase + index] = slot;
    }
}
