// A conservative depth pyramid for occlusion culling (GpuCuller's second phase). The scene's
// depth test is `less` with depth cleared to 1, so a texel keeps the FARTHEST depth of the
// pixels (and, multisampled, of every sample) it covers: whatever lies behind it lies behind
// everything drawn there. Level 0 is half the target's size, rounded up, and each level is half
// the one before, rounded up, so texel t of level k covers the pixels [t * 2^(k+1),
// (t + 1) * 2^(k+1)); reads past an odd edge clamp to the last pixel, which it covers anyway.

#if MULTISAMPLED
@group(0) @binding(0) var depth: texture_depth_multisampled_2d;
#else
@group(0) @binding(0) var depth: texture_depth_2d;
#endif
@group(0) @binding(1) var finer: texture_2d<f32>;  // The previous level (reduceLevel).
@group(0) @binding(2) var destination: texture_storage_2d<r32float, write>;

fn farthestDepthAt(pixel: vec2u) -> f32 {
#if MULTISAMPLED
    var farthest = 0.0;
    for (var sample = 0u; sample < textureNumSamples(depth); sample++) {
        farthest = max(farthest, textureLoad(depth, pixel, i32(sample)));
    }
    return farthest;
#else
    return textureLoad(depth, pixel, 0);
#endif
}

// The texels of the level above (or pixels) that texel `texel` reduces: [first, last].
struct Footprint {
    first: vec2u,
    last: vec2u,
}

fn footprint(texel: vec2u, sourceSize: vec2u) -> Footprint {
    let first = texel * 2u;
    let lastTexel = textureDimensions(destination) - 1u;
    return Footprint(first, min(select(first + 1u, sourceSize - 1u, texel == lastTexel),
                                sourceSize - 1u));
}

@compute @workgroup_size(8, 8)
fn reduceDepth(@builtin(global_invocation_id) id: vec3u) {
    if (any(id.xy >= textureDimensions(destination))) {
        return;
    }
    let area = footprint(id.xy, textureDimensions(depth));
    var farthest = 0.0;
    for (var y = area.first.y; y <= area.last.y; y++) {
        for (var x = area.first.x; x <= area.last.x; x++) {
            farthest = max(farthest, farthestDepthAt(vec2u(x, y)));
        }
    }
    textureStore(destination, id.xy, vec4f(farthest));
}

@compute @workgroup_size(8, 8)
fn reduceLevel(@builtin(global_invocation_id) id: vec3u) {
    if (any(id.xy >= textureDimensions(destination))) {
        return;
    }
    let area = footprint(id.xy, textureDimensions(finer));
    var farthest = 0.0;
    for (var y = area.first.y; y <= area.last.y; y++) {
        for (var x = area.first.x; x <= area.last.x; x++) {
            farthest = max(farthest, textureLoad(finer, vec2u(x, y), 0).r);
        }
    }
    textureStore(destination, id.xy, vec4f(farthest));
}
