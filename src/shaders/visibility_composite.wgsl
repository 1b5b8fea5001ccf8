// The visibility strategy's last step, inside the frame's render pass: a fullscreen triangle
// that copies each covered pixel's shaded colour into the target and its visibility-buffer depth
// into the depth attachment (for the background, the hardware-drawn rest of the scene and
// blended geometry after it); uncovered pixels are discarded.

@group(0) @binding(0) var<storage, read> visibility: array<vec2u>;
@group(0) @binding(1) var shaded: texture_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((vertex << 1u) & 2u), f32(vertex & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

struct FragmentOutput {
    @location(0) color: vec4f,
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fragmentMain(@builtin(position) position: vec4f) -> FragmentOutput {
    let pixel = vec2u(position.xy);
    let key = visibility[pixel.y * textureDimensions(shaded).x + pixel.x];
    if (key.y == 0u) {
        discard;
    }
    var output: FragmentOutput;
    output.color = textureLoad(shaded, pixel, 0);
    output.depth = bitcast<f32>(~key.y);
    return output;
}
