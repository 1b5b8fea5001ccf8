// The metallic-roughness BRDF of glTF 2.0 (Appendix B) and the lobes of the material extensions
// Encore shades: Trowbridge-Reitz/GGX distribution, height-correlated Smith visibility, Schlick
// Fresnel, Lambertian diffuse; the Charlie sheen distribution with Neubelt's visibility.
// `alpha` is always the perceptual roughness squared.

const kPi = 3.141592653589793;

fn fresnelSchlick(f0: vec3f, f90: vec3f, vDotH: f32) -> vec3f {
    let m = clamp(1.0 - vDotH, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (f90 - f0) * (m2 * m2 * m);
}

// Height-correlated Smith visibility V = G / (4 NdotL NdotV).
fn visibilityGgx(nDotL: f32, nDotV: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let viewTerm = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
    let lightTerm = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
    let sum = viewTerm + lightTerm;
    return select(0.0, 0.5 / sum, sum > 0.0);
}

fn distributionGgx(nDotH: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let f = (nDotH * nDotH) * (a2 - 1.0) + 1.0;
    return a2 / (kPi * f * f);
}

fn specularGgx(alpha: f32, nDotL: f32, nDotV: f32, nDotH: f32) -> f32 {
    return visibilityGgx(nDotL, nDotV, alpha) * distributionGgx(nDotH, alpha);
}

// Estevez and Kulla's "Charlie" sheen distribution.
fn distributionCharlie(sheenRoughness: f32, nDotH: f32) -> f32 {
    let alpha = max(sheenRoughness * sheenRoughness, 1e-6);
    let inverseAlpha = 1.0 / alpha;
    let sin2h = max(1.0 - nDotH * nDotH, 0.0);
    return (2.0 + inverseAlpha) * pow(sin2h, inverseAlpha * 0.5) / (2.0 * kPi);
}

fn visibilityNeubelt(nDotL: f32, nDotV: f32) -> f32 {
    return 1.0 / max(4.0 * (nDotL + nDotV - nDotL * nDotV), 1e-4);
}

// Fresnel-weighted specular reflectance under image-based lighting for the split-sum LUT
// values (scale, bias), with Fdez-Aguera's multiple-scattering compensation so that rough
// surfaces keep their energy (the white furnace stays white).
fn iblFresnel(f0: vec3f, specularWeight: f32, roughness: f32, nDotV: f32, lut: vec2f) -> vec3f {
    let fr = max(vec3f(1.0 - roughness), f0) - f0;
    let kS = f0 + fr * pow(1.0 - nDotV, 5.0);
    let singleScatter = specularWeight * (kS * lut.x + lut.y);
    let missing = 1.0 - (lut.x + lut.y);
    let averageFresnel = specularWeight * (f0 + (1.0 - f0) / 21.0);
    let multipleScatter = missing * singleScatter * averageFresnel / (1.0 - averageFresnel * missing);
    return singleScatter + multipleScatter;
}
