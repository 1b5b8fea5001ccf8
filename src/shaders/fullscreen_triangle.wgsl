// One triangle covering the viewport, drawn as three vertices without a vertex buffer: vertices
// (0,0), (2,0), (0,2) in uv, twice the viewport, whose visible part is the unit square.

fn fullscreenUv(index: u32) -> vec2f {
    return vec2f(f32((index << 1u) & 2u), f32(index & 2u));
}

// Its clip-space position, uv (0,0) at the bottom-left corner.
fn fullscreenPosition(index: u32) -> vec4f {
    return vec4f(fullscreenUv(index) * 2.0 - 1.0, 0.0, 1.0);
}
