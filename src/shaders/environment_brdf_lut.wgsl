// The split-sum BRDF table, texel (i, j) of a size x size texture at the pixel centre
// NdotV = (i + 0.5) / size, perceptual roughness = (j + 0.5) / size (alpha = roughness^2):
//  red, green: scale and bias of F0 in the integral of the GGX specular BRDF with
//              height-correlated Smith visibility times NdotL (Karis's split sum in the form of
//              Filament and the Khronos glTF Sample Renderer): F0 * red + green.
//  blue:       the directional albedo of the Charlie sheen lobe (Estevez and Kulla) with
//              Neubelt's visibility, sampled uniformly over the hemisphere, clamped to 1.

#include "environment_common.wgsl"

// The layout of the cube passes' parameters (one uniform slot format for all); only the
// sample count matters here.
struct Params {
    unused: u32,
    sampleCount: u32,
}

@group(0) @binding(0) var lut: texture_storage_2d<rgba16float, write>;
@group(0) @binding(1) var<uniform> params: Params;

fn visibilitySmithGgxCorrelated(nDotV: f32, nDotL: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let ggxV = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
    let ggxL = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
    return 0.5 / (ggxV + ggxL);
}

fn distributionCharlie(alpha: f32, nDotH: f32) -> f32 {
    let invAlpha = 1.0 / alpha;
    // Filament's floor on sin^2: keeps the power finite in half precision near NdotH = 1.
    let sin2h = max(1.0 - nDotH * nDotH, 0.0078125);
    return (2.0 + invAlpha) * pow(sin2h, invAlpha * 0.5) / (2.0 * kPi);
}

fn visibilityNeubelt(nDotV: f32, nDotL: f32) -> f32 {
    return 1.0 / (4.0 * (nDotL + nDotV - nDotL * nDotV));
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let size = textureDimensions(lut);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let nDotV = (f32(id.x) + 0.5) / f32(size.x);
    let roughness = (f32(id.y) + 0.5) / f32(size.y);
    let alpha = roughness * roughness;
    let v = vec3f(sqrt(1.0 - nDotV * nDotV), 0.0, nDotV);
    let count = params.sampleCount;

    // GGX with importance-sampled half vectors: pdf(l) = D NdotH / (4 VdotH), so each sample
    // contributes V_vis * 4 VdotH NdotL / NdotH (the D cancels).
    var scale = 0.0;
    var bias = 0.0;
    for (var i = 0u; i < count; i++) {
        let h = sampleGgx(hammersley(i, count), alpha);
        let vDotH = dot(v, h);
        let l = 2.0 * vDotH * h - v;
        let nDotL = l.z;
        if (nDotL > 0.0 && vDotH > 0.0) {
            let weight = visibilitySmithGgxCorrelated(nDotV, nDotL, alpha) * 4.0 * vDotH * nDotL /
                         h.z;
            let fresnel = pow(1.0 - vDotH, 5.0);
            scale += (1.0 - fresnel) * weight;
            bias += fresnel * weight;
        }
    }

    // Charlie: the lobe is wide, so uniform hemisphere samples (pdf 1 / (2 pi)) do well.
    let sheenAlpha = max(alpha, 1e-4);
    var sheen = 0.0;
    for (var i = 0u; i < count; i++) {
        let xi = hammersley(i, count);
        let nDotL = 1.0 - xi.x;  // In (0, 1]: never the horizon itself.
        let r = sqrt(1.0 - nDotL * nDotL);
        let phi = 2.0 * kPi * xi.y;
        let l = vec3f(r * cos(phi), r * sin(phi), nDotL);
        let h = normalize(v + l);
        sheen += distributionCharlie(sheenAlpha, h.z) * visibilityNeubelt(nDotV, nDotL) * nDotL;
    }
    // Neubelt's visibility is not a shadowing term, and with it the albedo exceeds 1 at grazing
    // angles for sheen roughness below about 0.3 (it grows like 1 / sqrt(alpha)). The value is
    // used for albedo scaling, 1 - max(sheenColor) * E, which must not go negative: clamp.
    sheen = min(sheen * 2.0 * kPi / f32(count), 1.0);

    textureStore(lut, id.xy, vec4f(scale / f32(count), bias / f32(count), sheen, 1.0));
}
