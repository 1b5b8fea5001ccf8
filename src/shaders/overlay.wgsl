// The viewer's overlay (view::Overlay): coloured triangles in window pixels (text from
// stb_easy_font, panels, graphs), blended over the presented image.

struct Viewport {
    size: vec2f,
}

@group(0) @binding(0) var<uniform> viewport: Viewport;

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) color: vec4f,
}

@vertex
fn vertexMain(@location(0) pixel: vec2f, @location(1) color: vec4f) -> VertexOutput {
    var output: VertexOutput;
    let ndc = pixel / viewport.size * vec2f(2.0, -2.0) + vec2f(-1.0, 1.0);
    output.position = vec4f(ndc, 0.0, 1.0);
    output.color = color;
    return output;
}

@fragment
fn fragmentMain(input: VertexOutput) -> @location(0) vec4f {
    return input.color;
}
