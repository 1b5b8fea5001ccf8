// Equirectangular panorama -> level 0 of the source cube map, one invocation per texel with
// the six faces along z. Directions follow image::HdrImage: row 0 is +Y, and longitude
// phi = atan2(z, x) grows with the column, phi = 2 pi u.

#include "environment_common.wgsl"

@group(0) @binding(0) var panorama: texture_2d<f32>;
@group(0) @binding(1) var panoramaSampler: sampler;  // Repeats in u, clamps in v.
@group(0) @binding(2) var cube: texture_storage_2d_array<rgba16float, write>;

fn panoramaUv(d: vec3f) -> vec2f {
    let u = fract(atan2(d.z, d.x) / (2.0 * kPi) + 1.0);
    let v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
    return vec2f(u, v);
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let size = textureDimensions(cube).x;
    if (id.x >= size || id.y >= size) {
        return;
    }
    // Four bilinear samples per texel: a panorama is often denser than the cube (a 2048-wide
    // one has twice the texels per degree of a 256 face), and one tap would alias.
    var sum = vec3f(0.0);
    for (var i = 0u; i < 4u; i++) {
        let offset = vec2f(f32(i & 1u), f32(i >> 1u)) * 0.5 - 0.25;
        let d = cubeDirection(id.z, (vec2f(id.xy) + 0.5 + offset) / f32(size));
        sum += textureSampleLevel(panorama, panoramaSampler, panoramaUv(d), 0.0).rgb;
    }
    textureStore(cube, id.xy, id.z, vec4f(sum * 0.25, 1.0));
}
