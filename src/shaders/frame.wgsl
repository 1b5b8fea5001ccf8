// Group 0: per-frame data, shared by every pipeline (bind groups are ordered by how often they
// change: frame, then instances, then material).
struct Frame {
    projection: mat4x4f,
    view: mat4x4f,
    cameraPosition: vec3f,
    time: f32,
    // Where this view lies in the render target, in texture coordinates: offset xy, size zw
    // (several views side by side); the transmission pass's copy is read through it.
    viewRect: vec4f,
}
#if VIEW_SLOTS
// Set per pixel from the view it lies in (visibility_shade.wgsl shades several views at once).
var<private> frame: Frame;
#else
@group(0) @binding(0) var<uniform> frame: Frame;
#endif
