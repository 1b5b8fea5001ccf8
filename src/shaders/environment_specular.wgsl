// One face of one level of the specular cube: the environment prefiltered for the GGX lobe of
// one roughness under the usual N = V = R assumption, weighted by NdotL (Karis, "Real Shading
// in Unreal Engine 4"). Samples read the source mip that matches their pdf, so a few hundred
// samples give a smooth result.

#include "environment_common.wgsl"

struct Params {
    face: u32,
    sampleCount: u32,
    roughness: f32,             // Perceptual; alpha = roughness^2.
    sourceTexelSolidAngle: f32, // 4 pi / (6 * size^2) of the source's level 0.
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
    let alpha = params.roughness * params.roughness;
    var sum = vec3f(0.0);
    var weight = 0.0;
    for (var i = 0u; i < params.sampleCount; i++) {
        let hTangent = sampleGgx(hammersley(i, params.sampleCount), alpha);
        // With V = N, L = reflect(-N, H) and NdotL = 2 NdotH^2 - 1 in tangent space.
        let nDotL = 2.0 * hTangent.z * hTangent.z - 1.0;
        if (nDotL > 0.0) {
            let h = tangentToWorld(hTangent, n);
            let l = 2.0 * hTangent.z * h - n;
            // pdf over L = D(h) NdotH / (4 VdotH), and VdotH = NdotH here.
            let pdf = distributionGgx(hTangent.z, alpha) * 0.25;
            let lod = sourceLod(pdf, params.sampleCount, params.sourceTexelSolidAngle,
                                params.sourceMaxLod);
            sum += textureSampleLevel(source, sourceSampler, l, lod).rgb * nDotL;
            weight += nDotL;
        }
    }
    textureStore(destination, id.xy, params.face, vec4f(sum / max(weight, 1e-6), 1.0));
}
