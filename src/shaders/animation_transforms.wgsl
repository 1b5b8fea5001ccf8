// GPU animation, pass 3 (GpuAnimation): a node's world matrix times a fixed matrix, with its
// normal matrix, written where the vertex shaders read it. For instances the fixed matrix is the
// EXT_mesh_gpu_instancing transform and the output the strategy's instance transforms; for
// joints it is the inverse bind matrix and the output AnimationBuffers' joint matrices.

struct Record {
    node: u32,
    slot: u32,  // Index into outputs.
    pad0: u32,
    pad1: u32,
    transform: mat4x4f,
}

struct Transform {
    world: mat4x4f,
    normal: mat4x4f,
}

@group(0) @binding(0) var<storage, read> records: array<Record>;
@group(0) @binding(1) var<storage, read> worlds: array<mat4x4f>;
@group(0) @binding(2) var<storage, read_write> outputs: array<Transform>;

override kWorkgroupSize: u32 = 64;

fn isFinite3(m: mat3x3f) -> bool {
    let big = vec3f(3.4028234e38);
    return all(abs(m[0]) <= big) && all(abs(m[1]) <= big) && all(abs(m[2]) <= big);
}

// The inverse transpose of the upper 3x3, as scene::normalMatrixOf: the cofactor matrix over the
// determinant; a singular matrix keeps the cofactor matrix, a rank-one or non-finite one the
// identity.
fn normalMatrixOf(m: mat4x4f) -> mat4x4f {
    let a = mat3x3f(m[0].xyz, m[1].xyz, m[2].xyz);
    var cofactor: mat3x3f;
    for (var c = 0u; c < 3u; c++) {
        for (var r = 0u; r < 3u; r++) {
            let c1 = (c + 1u) % 3u;
            let c2 = (c + 2u) % 3u;
            let r1 = (r + 1u) % 3u;
            let r2 = (r + 2u) % 3u;
            cofactor[c][r] = a[c1][r1] * a[c2][r2] - a[c1][r2] * a[c2][r1];
        }
    }
    let det = determinant(a);
    var result = mat3x3f(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    let inverseTranspose = cofactor * (1.0 / det);
    let zero = all(cofactor[0] == vec3f(0.0)) && all(cofactor[1] == vec3f(0.0)) &&
               all(cofactor[2] == vec3f(0.0));
    if (abs(det) > 1e-30 && abs(det) <= 3.4028234e38 && isFinite3(inverseTranspose)) {
        result = inverseTranspose;
    } else if (isFinite3(cofactor) && !zero) {
        result = cofactor;
    }
    return mat4x4f(vec4f(result[0], 0.0), vec4f(result[1], 0.0), vec4f(result[2], 0.0),
                   vec4f(0.0, 0.0, 0.0, 1.0));
}

@compute @workgroup_size(kWorkgroupSize)
fn nodeTransforms(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= arrayLength(&records)) {
        return;
    }
    let record = records[id.x];
    let world = worlds[record.node] * record.transform;
    // The normal matrix's fourth column holds the instance's segmentation ids: kept.
    var normal = normalMatrixOf(world);
    normal[3] = outputs[record.slot].normal[3];
    outputs[record.slot] = Transform(world, normal);
}
