// The pass images of a fragment (mesh.wgsl's PASS_TARGETS variant: encore batch's passes drawn
// in the colour frame's render pass, render/PassTargets.h). shadeSurface records what the debug
// channels would write; fragmentMain writes them to the extra colour targets, each with the
// fragment's alpha, so that blending and the multisample resolve treat them as the debug
// channels' frames treat theirs.

struct SurfacePasses {
    normal: vec3f,    // n * 0.5 + 0.5, as DebugChannel::Normal.
    albedo: vec3f,    // The base colour, as DebugChannel::BaseColor.
    material: vec3f,  // Occlusion, roughness, metallic, as DebugChannel::Material.
    depth: f32,       // Along the camera axis, as DebugChannel::Depth.
}
var<private> surfacePasses: SurfacePasses;

struct PassOutputs {
    @location(0) color: vec4f,
    @location(1) normal: vec4f,
    @location(2) albedo: vec4f,
    @location(3) material: vec4f,
    // Depth, then the segmentation id split as segmentationColor splits it, exact in halves.
    @location(4) depthAndId: vec4f,
}

fn passOutputs(color: vec4f, alpha: f32, id: f32) -> PassOutputs {
    let high = floor(id / 256.0);
    return PassOutputs(color, vec4f(surfacePasses.normal, alpha), vec4f(surfacePasses.albedo, alpha),
                       vec4f(surfacePasses.material, alpha),
                       vec4f(surfacePasses.depth, id - high * 256.0, high, alpha));
}
