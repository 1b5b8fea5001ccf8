// The final pass: the linear HDR image of the frame (straight colour premultiplied by coverage:
// alpha is 0 where nothing was drawn) is exposed, tone mapped and composited over the
// background, then written to the sRGB output target (the hardware encodes sRGB).

struct ToneMapping {
    exposure: f32,
    // 0 none (clamp), 1 Khronos PBR Neutral, 2 ACES (Stephen Hill's fit).
    mapping: u32,
    // 0 a colour (backgroundColor, linear), 1 transparent (straight alpha out), 2 the frame
    // already holds its background (the environment, drawn opaque by sky.wgsl).
    background: u32,
    padding: u32,
    backgroundColor: vec4f,
}

@group(0) @binding(0) var<uniform> toneMapping: ToneMapping;
@group(0) @binding(1) var hdrImage: texture_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    // One triangle covering the viewport.
    let uv = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

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

fn toneMap(color: vec3f) -> vec3f {
    let exposed = max(color, vec3f(0.0)) * toneMapping.exposure;
    switch (toneMapping.mapping) {
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

@fragment
fn fragmentMain(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let hdr = textureLoad(hdrImage, vec2i(position.xy), 0);
    let coverage = clamp(hdr.a, 0.0, 1.0);
    // Tone-map the surface's own colour, then weigh it by coverage: antialiased edges blend
    // mapped colours, as a display would.
    let surface = select(vec3f(0.0), toneMap(hdr.rgb / max(coverage, 1e-6)), coverage > 0.0);
    switch (toneMapping.background) {
        case 1u: {
            return vec4f(surface, coverage);
        }
        case 2u: {
            return vec4f(toneMap(hdr.rgb), 1.0);
        }
        default: {
            return vec4f(surface * coverage + toneMapping.backgroundColor.rgb * (1.0 - coverage),
                         1.0);
        }
    }
}
