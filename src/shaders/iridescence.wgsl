// KHR_materials_iridescence: the reflectance of a thin dielectric film over the surface, after
// Belcour and Barla ("A Practical Extension to Microfacet Theory for the Modeling of Varying
// Iridescence", 2017) as the Khronos Sample Renderer evaluates it: the light reflected at the
// film's top and the light reflected by the base below interfere (Schlick Fresnel at both
// interfaces, the phase of the optical path through the film), and the interference is
// integrated over the visible spectrum against the CIE matching functions, in closed form
// (Gaussian fits in Fourier space), then taken to linear sRGB. Needs brdf.wgsl (kPi).

// CIE XYZ to linear sRGB (Rec. 709 primaries, D65 white), as columns.
const kXyzToLinearSrgb = mat3x3f(vec3f(3.2404542, -0.9692660, 0.0556434),
                                 vec3f(-1.5371385, 1.8760108, -0.2040259),
                                 vec3f(-0.4985314, 0.0415560, 1.0572252));

fn schlickScalar(f0: f32, cosine: f32) -> f32 {
    let m = clamp(1.0 - cosine, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// The spectral response, in linear sRGB, of an interference term whose optical path difference
// is `opd` nanometres and whose phase shift is `shift` radians per channel.
fn filmSensitivity(opd: f32, shift: vec3f) -> vec3f {
    let phase = 2.0 * kPi * opd * 1.0e-9;
    let phase2 = phase * phase;
    // Each matching function as a Gaussian: weight, mean frequency, variance.
    let weight = vec3f(5.4856e-13, 4.4201e-13, 5.2481e-13);
    let mean = vec3f(1.6810e+06, 1.7953e+06, 2.2084e+06);
    let variance = vec3f(4.3278e+09, 9.3046e+09, 6.6121e+09);
    var xyz = weight * sqrt(2.0 * kPi * variance) * cos(mean * phase + shift) *
              exp(-phase2 * variance);
    // X has a second lobe (the blue bump of x-bar).
    xyz.x += 9.7470e-14 * sqrt(2.0 * kPi * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
             exp(-4.5282e+09 * phase2);
    return kXyzToLinearSrgb * (xyz / 1.0685e-7);
}

// The reflectance (rgb) of a film of index `filmIor` and `thickness` nanometres, seen from air
// at cosine `cosView`, over a base whose reflectance at normal incidence is `baseF0`.
fn iridescenceFresnel(filmIor: f32, cosView: f32, thickness: f32, baseF0: vec3f) -> vec3f {
    // A vanishing film becomes air, so the base shows through unchanged.
    let ior = mix(1.0, filmIor, smoothstep(0.0, 0.03, thickness));
    let cosFilm2 = 1.0 - (1.0 - cosView * cosView) / (ior * ior);  // Snell's law.
    if (cosFilm2 < 0.0) {
        return vec3f(1.0);  // Total internal reflection.
    }
    let cosFilm = sqrt(cosFilm2);

    // Top interface (air to film), and the phase it adds seen from inside.
    let topF0 = (ior - 1.0) * (ior - 1.0) / ((ior + 1.0) * (ior + 1.0));
    let r12 = schlickScalar(topF0, cosView);
    let t121 = 1.0 - r12;
    let phi21 = select(kPi, 0.0, ior < 1.0);
    // Bottom interface (film to base): the base's index from its reflectance.
    let sqrtBase = sqrt(clamp(baseF0, vec3f(0.0), vec3f(0.9999)));
    let baseIor = (1.0 + sqrtBase) / (1.0 - sqrtBase);
    let bottomRatio = (baseIor - ior) / (baseIor + ior);
    let r23 = fresnelSchlick(bottomRatio * bottomRatio, vec3f(1.0), cosFilm);
    let phi23 = select(vec3f(0.0), vec3f(kPi), baseIor < vec3f(ior));

    let opd = 2.0 * ior * thickness * cosFilm;
    let phi = vec3f(phi21) + phi23;
    let r123 = clamp(r12 * r23, vec3f(1e-5), vec3f(0.9999));
    let amplitude = sqrt(r123);
    // The incoherent sum (m = 0), then the first two interference orders.
    let transmitted = t121 * t121 * r23 / (1.0 - r123);
    var reflectance = r12 + transmitted;
    var order = transmitted - t121;
    for (var m = 1; m <= 2; m++) {
        order *= amplitude;
        reflectance += order * 2.0 * filmSensitivity(f32(m) * opd, f32(m) * phi);
    }
    return max(reflectance, vec3f(0.0));  // Out-of-gamut colours can go negative.
}

// Layer `layer` over `base`, weighted per channel by `weight` (the base keeps what the
// strongest channel leaves).
fn mixPerChannel(base: vec3f, layer: vec3f, weight: vec3f) -> vec3f {
    return (1.0 - max(weight.x, max(weight.y, weight.z))) * base + weight * layer;
}
