// The final pass of an HDR render target (RenderTargetOptions::hdr; targets without it tone map
// in the scene shaders): the linear HDR image of the frame (straight colour premultiplied by
// coverage: alpha is 0 where nothing was drawn) is exposed, tone mapped and composited over the
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

#include "fullscreen_triangle.wgsl"
#include "tone_map.wgsl"

@group(0) @binding(0) var<uniform> toneMapping: ToneMapping;
@group(0) @binding(1) var hdrImage: texture_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    return fullscreenPosition(index);
}

@fragment
fn fragmentMain(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let hdr = textureLoad(hdrImage, vec2i(position.xy), 0);
    let coverage = clamp(hdr.a, 0.0, 1.0);
    // Tone-map the surface's own colour, then weigh it by coverage: antialiased edges blend
    // mapped colours, as a display would.
    let surface = select(vec3f(0.0), toneMap(hdr.rgb / max(coverage, 1e-6), toneMapping.exposure, toneMapping.mapping), coverage > 0.0);
    switch (toneMapping.background) {
        case 1u: {
            return vec4f(surface, coverage);
        }
        case 2u: {
            return vec4f(toneMap(hdr.rgb, toneMapping.exposure, toneMapping.mapping), 1.0);
        }
        default: {
            return vec4f(surface * coverage + toneMapping.backgroundColor.rgb * (1.0 - coverage),
                         1.0);
        }
    }
}
