// GPU animation, pass 2 (GpuAnimation): world matrices, one depth level of the hierarchy per
// dispatch, parents' levels first: world = world(parent) * local. Only nodes below an animated
// node are listed; every other node keeps the rest world matrix the buffer was created with.

const kNone: u32 = 0xffffffffu;

struct WorldNode {
    node: u32,
    parent: u32,  // kNone for a root.
}

@group(0) @binding(0) var<uniform> level: vec4u;  // x: first entry of worldNodes, y: count.
@group(0) @binding(1) var<storage, read> worldNodes: array<WorldNode>;
@group(0) @binding(2) var<storage, read> locals: array<mat4x4f>;
@group(0) @binding(3) var<storage, read_write> worlds: array<mat4x4f>;

override kWorkgroupSize: u32 = 64;

@compute @workgroup_size(kWorkgroupSize)
fn worldMatrices(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= level.y) {
        return;
    }
    let entry = worldNodes[level.x + id.x];
    let nodeLocal = locals[entry.node];
    if (entry.parent == kNone) {
        worlds[entry.node] = nodeLocal;
    } else {
        worlds[entry.node] = worlds[entry.parent] * nodeLocal;
    }
}
