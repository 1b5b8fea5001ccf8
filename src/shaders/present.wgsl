// Copies the renderer's output into a window's surface texture value for value (view::Presenter):
// an sRGB source view into an sRGB surface (decoded, then encoded again: exact for 8-bit
// values), or the source's bytes into a linear surface. A full-screen triangle.

#include "fullscreen_triangle.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    return fullscreenPosition(index);
}

@fragment
fn fragmentMain(@builtin(position) position: vec4f) -> @location(0) vec4f {
    return textureLoad(source, vec2i(position.xy), 0);
}
