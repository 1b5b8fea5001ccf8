// The visibility buffer cleared (depth and id zero: nothing drawn) by a dispatch at the start of
// the frame's first compute pass rather than a clearBuffer command: the frame's GPU time then
// counts it (a transfer between passes falls outside every pass's timestamps), and it may run
// beside the culling, which does not touch the buffer.
@group(0) @binding(0) var<storage, read_write> visibility: array<vec2u>;

@compute @workgroup_size(256)
fn clearMain(@builtin(global_invocation_id) id: vec3u,
             @builtin(num_workgroups) groups: vec3u) {
    let stride = groups.x * 256u;
    for (var entry = id.x; entry < arrayLength(&visibility); entry += stride) {
        visibility[entry] = vec2u(0u);
    }
}
