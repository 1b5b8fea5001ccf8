// One mip level of a cube map from the level above it: a 2x2 box filter per face (faces along
// z). Odd sizes drop their last row and column, which only cube sizes that are not powers of
// two have.

@group(0) @binding(0) var source: texture_2d_array<f32>;  // One level, six layers.
@group(0) @binding(1) var destination: texture_storage_2d_array<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let size = textureDimensions(destination).x;
    if (id.x >= size || id.y >= size) {
        return;
    }
    let last = textureDimensions(source).x - 1u;
    let base = id.xy * 2u;
    var sum = vec4f(0.0);
    for (var i = 0u; i < 4u; i++) {
        let texel = min(base + vec2u(i & 1u, i >> 1u), vec2u(last));
        sum += textureLoad(source, texel, id.z, 0);
    }
    textureStore(destination, id.xy, id.z, sum * 0.25);
}
