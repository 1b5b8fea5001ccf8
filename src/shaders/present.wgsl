// Copies the renderer's output into a window's surface texture value for value (view::Presenter):
// an sRGB source view into an sRGB surface (decoded, then encoded again: exact for 8-bit
// values), or the source's bytes into a linear surface. A full-screen triangle.

@group(0) @binding(0) var source: texture_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fragmentMain(@builtin(position) position: vec4f) -> @location(0) vec4f {
    return textureLoad(source, vec2i(position.xy), 0);
}
