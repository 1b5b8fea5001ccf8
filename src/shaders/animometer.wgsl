// The Animometer benchmark scene (render/Animometer), after MotionMark's Animometer as ported
// by the WebGPU samples: every triangle is the same three vertices, placed and spun by its own
// parameters in group 1. Only the time in group 0 changes per frame, so a frame's draws can be
// recorded once into a render bundle.

struct Time {
    seconds: f32,
}

// One triangle's parameters; each lives in its own 256-byte slot of one uniform buffer.
struct Triangle {
    scale: f32,
    offsetX: f32,         // Centre in clip space.
    offsetY: f32,
    scalar: f32,          // Spin speed.
    scalarOffset: f32,    // Spin phase, so triangles do not turn in step.
}

@group(0) @binding(0) var<uniform> time: Time;
@group(1) @binding(0) var<uniform> triangle: Triangle;

const kTau = 6.283185307179586;

struct VertexOutput {
    @builtin(position) position: vec4f,
    @location(0) color: vec4f,
}

@vertex
fn vertexMain(@location(0) corner: vec2f) -> VertexOutput {
    // A triangle wave in [0, 1]: each triangle turns one way through a full circle and back.
    let phase = fract(triangle.scalarOffset + time.seconds * triangle.scalar * 0.1);
    let fade = 1.0 - abs(phase * 2.0 - 1.0);
    let angle = kTau * fade;
    let c = cos(angle);
    let s = sin(angle);
    let local = corner * triangle.scale;
    let rotated = vec2f(local.x * c - local.y * s, local.x * s + local.y * c);
    let position = rotated + vec2f(triangle.offsetX, triangle.offsetY);

    var output: VertexOutput;
    output.position = vec4f(position, 0.0, 1.0);
    // Colour from where the vertex is on screen, shaded by the spin, so motion is visible.
    output.color = vec4f(0.5 + 0.5 * position.x, 0.5 + 0.5 * position.y, fade, 1.0);
    return output;
}

@fragment
fn fragmentMain(input: VertexOutput) -> @location(0) vec4f {
    return input.color;
}
