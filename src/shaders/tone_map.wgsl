// The display transform: exposure and a tone-mapping operator, from linear scene-referred colour
// to display colour in 0..1 (the sRGB target encodes it). Used by the scene shaders, which tone
// map as they shade (scene_lighting.wgsl's displayColor), and by the tone-mapping pass of HDR
// targets (tone_mapping.wgsl).

// Khronos PBR Neutral (the Khronos 3D Commerce tone mapper): colours below about 0.8 pass
// nearly unchanged, highlights compress towards white with a little desaturation.
fn pbrNeutral(input: vec3f) -> vec3f {
    let startCompression = 0.8 - 0.04;
    let desaturation = 0.15;
    let x = min(input.r, min(input.g, input.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    var color = input - offset;
    let peak = max(color.r, max(color.g, color.b));
    if (peak < startCompression) {
        return color;
    }
    let d = 1.0 - startCompression;
    let newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    let g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(color, vec3f(newPeak), g);
}

// ACES filmic, Stephen Hill's fit of the RRT and ODT (sRGB primitives in and out).
fn acesHill(input: vec3f) -> vec3f {
    let toAces = mat3x3f(vec3f(0.59719, 0.07600, 0.02840), vec3f(0.35458, 0.90834, 0.13383),
                         vec3f(0.04823, 0.01566, 0.83777));
    let fromAces = mat3x3f(vec3f(1.60475, -0.10208, -0.00327),
                           vec3f(-0.53108, 1.10813, -0.07276),
                           vec3f(-0.07367, -0.00605, 1.07602));
    let v = toAces * input;
    let a = v * (v + 0.0245786) - 0.000090537;
    let b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return clamp(fromAces * (a / b), vec3f(0.0), vec3f(1.0));
}

// Exposure, then the operator: 0 none (clamp), 1 Khronos PBR Neutral, 2 ACES (Hill).
fn toneMap(color: vec3f, exposure: f32, mapping: u32) -> vec3f {
    let exposed = max(color, vec3f(0.0)) * exposure;
    switch (mapping) {
        case 1u: {
            return clamp(pbrNeutral(exposed), vec3f(0.0), vec3f(1.0));
        }
        case 2u: {
            return acesHill(exposed);
        }
        default: {
            return clamp(exposed, vec3f(0.0), vec3f(1.0));
        }
    }
}
