// What the visibility strategy culls by, shared by its cull (items, visibility_cull.wgsl) and its
// raster passes (clusters, visibility_raster.wgsl): the frame's culling uniform, the depth
// pyramid of the first occlusion phase, and the tests of a sphere or a box against them. Needs
// visibility_geometry.wgsl and pyramid_occlusion.wgsl.

#include "culling_view.wgsl"

@group(1) @binding(10) var<uniform> culling: Culling;
// Read in the second phase only (the first phase's pyramid is still last frame's).
@group(1) @binding(12) var depthPyramid: texture_2d<f32>;

// Whether a sphere (world space) lies wholly outside one of the frustum's planes.
fn sphereOutsideFrustum(center: vec3f, radius: f32) -> bool {
    if (culling.frustumTest == 0u) {
        return false;
    }
    for (var i = 0u; i < 6u; i++) {
        // The sign of the rounded sum is the exact sum's: the same test as distance < -radius.
        if (sphereReach(i, center, radius) < 0.0) {
            return true;
        }
    }
    return false;
}

// Whether the pyramid proves a box hidden (`center` and `extent` in object space, moved by
// `world`): the nearest depth of its eight corners lies behind the farthest depth drawn anywhere
// over the pixels the box covers (as culling.wgsl's isOccluded).
fn boxOccluded(center: vec3f, extent: vec3f, world: mat4x4f) -> bool {
    let viewport = vec2f(f32(params.viewportWidth), f32(params.viewportHeight));
    var low = vec2f(3.4e38);
    var high = vec2f(-3.4e38);
    var nearestDepth = 1.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let side = select(vec3f(-1.0), vec3f(1.0),
                          vec3<bool>((corner & 1u) != 0u, (corner & 2u) != 0u,
                                     (corner & 4u) != 0u));
        let clip = culling.viewProjection * (world * vec4f(center + side * extent, 1.0));
        if (clip.w <= 1e-6 || clip.z < 0.0) {
            return false;  // The box reaches the near plane: it may cover the whole view.
        }
        let ndc = clip.xyz / clip.w;
        let pixel = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * viewport;
        low = min(low, pixel);
        high = max(high, pixel);
        nearestDepth = min(nearestDepth, ndc.z);
    }
    return pyramidHides(depthPyramid, viewport, low, high, nearestDepth);
}
