// Downsamples one mip level into the next (render/MipmapGenerator). The pass draws a single
// triangle that covers the destination level; each fragment takes one bilinear sample at its
// centre, which for even sizes is exactly the mean of the 2x2 source texels below it.
//
// The source is a single-level view, so the sample always reads that level. For sRGB textures
// the view decodes to linear before filtering and the sRGB attachment encodes again, so the
// average is taken in linear space.

#include "fullscreen_triangle.wgsl"

@group(0) @binding(0) var sourceSampler: sampler;
@group(0) @binding(1) var sourceLevel: texture_2d<f32>;

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) uv: vec2f,
}

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> VertexOutput {
    // v grows downwards, like texture rows.
    let uv = fullscreenUv(index);
    var output: VertexOutput;
    output.position = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    output.uv = uv;
    return output;
}

@fragment
fn fragmentMain(input: VertexOutput) -> @location(0) vec4f {
    return textureSampleLevel(sourceLevel, sourceSampler, input.uv, 0.0);
}
