// One face of the irradiance cube: for each normal n, (1 / pi) * integral of L(l) * NdotL over
// the hemisphere, the cosine-weighted average radiance. Cosine-weighted samples have pdf
// NdotL / pi, so the estimate is the plain mean of the samples (a uniform environment gives
// exactly its radiance), each read from the source mip that matches its pdf.

#include "environment_common.wgsl"

struct Params {
    face: u32,
    sampleCount: u32,
    unused: f32,
    sourceTexelSolidAngle: f32,
    sourceMaxLod: f32,
}

@group(0) @binding(0) var source: texture_cube<f32>;
@group(0) @binding(1) var sourceSampler: sampler;
@group(0) @binding(2) var destination: texture_storage_2d_array<rgba16float, write>;
@group(0) @binding(3) var<uniform> params: Params;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let size = textureDimensions(destination).x;
    if (id.x >= size || id.y >= size) {
        return;
    }
    let n = texelDirection(params.face, id.xy, size);
    var sum = vec3f(0.0);
    for (var i = 0u; i < params.sampleCount; i++) {
        let xi = hammersley(i, params.sampleCount);
        let r = sqrt(xi.x);
        let phi = 2.0 * kPi * xi.y;
        let nDotL = sqrt(1.0 - xi.x);
        let l = tangentToWorld(vec3f(r * cos(phi), r * sin(phi), nDotL), n);
        let lod = sourceLod(nDotL / kPi, params.sampleCount, params.sourceTexelSolidAngle,
                            params.sourceMaxLod);
        sum += textureSampleLevel(source, sourceSampler, l, lod).rgb;
    }
    textureStore(destination, id.xy, params.face, vec4f(sum / f32(params.sampleCount), 1.0));
}
