// The environment as the background of a view: one triangle covering the viewport, drawn first
// in each scene pass with depth testing off. The view ray comes from the frame's camera, so the
// same pipeline serves every view of a multi-view frame.
#include "frame.wgsl"
#include "fullscreen_triangle.wgsl"
#include "scene_lighting.wgsl"

struct SkyOutput {
    @builtin(position) position: vec4f,
    @location(0) ndc: vec2f,
}

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> SkyOutput {
    let uv = fullscreenUv(index);
    var output: SkyOutput;
    output.ndc = uv * 2.0 - 1.0;
    output.position = vec4f(output.ndc, 1.0, 1.0);
    return output;
}

@fragment
fn fragmentMain(input: SkyOutput) -> @location(0) vec4f {
    var viewRay = vec3f(0.0, 0.0, -1.0);  // Orthographic cameras see one direction.
    if (frame.projection[3][3] != 1.0) {
        // Perspective: undo the projection's scale and offset (off-centre frusta included).
        viewRay = vec3f((input.ndc.x + frame.projection[2][0]) / frame.projection[0][0],
                        (input.ndc.y + frame.projection[2][1]) / frame.projection[1][1], -1.0);
    }
    // The view matrix is a rigid transform: its rotation's transpose is its inverse.
    let rotation = mat3x3f(frame.view[0].xyz, frame.view[1].xyz, frame.view[2].xyz);
    let direction = normalize(transpose(rotation) * viewRay);
    return displayColor(vec4f(environmentRadiance(direction, 0.0), 1.0));
}
