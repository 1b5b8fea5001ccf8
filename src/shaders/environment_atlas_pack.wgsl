// Writes one region of the environment atlas (environment_atlas.wgsl), borders included, from
// the maps the other environment passes computed: one invocation per texel of the region.
//  packCube:  one level of a cube map as six cells. Interior texels sample the face at their own
//             texel centres (so they are the face's texels); border texels sample the direction
//             of the face's plane continued past the edge.
//  packTable: a 2D table (the BRDF lookup table) as it is, its border repeating the edge.

#include "environment_common.wgsl"

struct Params {
    origin: vec2u,  // The region's first texel, border included.
    size: u32,      // A face's (or the table's) interior texels per side.
    level: f32,     // packCube: the cube's mip level.
}

@group(0) @binding(0) var cube: texture_cube<f32>;
@group(0) @binding(1) var cubeSampler: sampler;
@group(0) @binding(2) var atlas: texture_storage_2d<rgba16float, write>;
@group(0) @binding(3) var<uniform> params: Params;
@group(0) @binding(4) var table: texture_2d<f32>;

@compute @workgroup_size(8, 8, 1)
fn packCube(@builtin(global_invocation_id) id: vec3u) {
    let span = params.size + 2u;
    if (id.x >= 3u * span || id.y >= 2u * span) {
        return;
    }
    let cell = id.xy / span;
    let face = cell.y * 3u + cell.x;
    // Texel centres, the border's half a texel outside 0..1.
    let uv = (vec2f(id.xy - cell * span) - 0.5) / f32(params.size);
    // cubeDirection takes the face's plane past its edges for uv outside 0..1.
    let d = cubeDirection(face, uv);
    let radiance = textureSampleLevel(cube, cubeSampler, d, params.level).rgb;
    textureStore(atlas, params.origin + id.xy, vec4f(radiance, 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn packTable(@builtin(global_invocation_id) id: vec3u) {
    if (id.x >= params.size + 2u || id.y >= params.size + 2u) {
        return;
    }
    let texel = clamp(vec2i(id.xy) - 1, vec2i(0), vec2i(i32(params.size) - 1));
    textureStore(atlas, params.origin + id.xy, textureLoad(table, texel, 0));
}
