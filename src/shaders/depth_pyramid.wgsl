// A conservative depth pyramid for occlusion culling (GpuCuller's second phase). The scene's
// depth test is `less` with depth cleared to 1, so a texel keeps the FARTHEST depth of the
// pixels (and, multisampled, of every sample) it covers: whatever lies behind it lies behind
// everything drawn there.
//
// Texel t of level k covers the pixels [t * 2^(k+1), (t + 1) * 2^(k+1)), so level k holds
// ceil(depth size / 2^(k+1)) texels a side (`levelSize`) and each texel reduces exactly the 2x2
// texels below it: no texel straddles another's footprint, and a workgroup can reduce a tile
// through several levels on its own. The texture is a power of two a side (mips round down, the
// levels' sizes here round up), so the texels a level holds sit in its top-left corner.
//
// A dispatch writes up to four levels (WebGPU's default limit of storage textures per stage):
// each 16x16 workgroup reduces its tile of the first level, then halves it in workgroup memory
// three times. Texels past a level's size hold 0, which the max ignores.
//
// VISIBILITY_BUFFER: level 0 reduces the visibility strategy's buffer instead of a depth texture
// (`samples` (id, ~depth bits) pairs per pixel, row by row; 0 where nothing was drawn: depth 1).

#if VISIBILITY_BUFFER
@group(0) @binding(0) var<storage, read> visibility: array<vec2u>;
#elif MULTISAMPLED
@group(0) @binding(0) var depth: texture_depth_multisampled_2d;
#else
@group(0) @binding(0) var depth: texture_depth_2d;
#endif
@group(0) @binding(1) var finer: texture_2d<f32>;  // Level firstLevel - 1 (reduceLevels).

struct Reduction {
    depthSize: vec2u,
    firstLevel: u32,
    levelCount: u32,  // 1 to 4: the levels this dispatch writes, from firstLevel.
    samples: u32,  // VISIBILITY_BUFFER: entries per pixel.
}
@group(0) @binding(2) var<uniform> reduction: Reduction;
@group(0) @binding(3) var level0: texture_storage_2d<r32float, write>;
@group(0) @binding(4) var level1: texture_storage_2d<r32float, write>;
@group(0) @binding(5) var level2: texture_storage_2d<r32float, write>;
@group(0) @binding(6) var level3: texture_storage_2d<r32float, write>;

const kTile = 16u;
var<workgroup> farthest: array<f32, 256>;  // kTile * kTile

fn levelSize(level: u32) -> vec2u {
    let texelPixels = 1u << (level + 1u);
    return (reduction.depthSize + vec2u(texelPixels - 1u)) / texelPixels;
}

fn storeLevel(step: u32, texel: vec2u, value: f32) {
    if (step >= reduction.levelCount || any(texel >= levelSize(reduction.firstLevel + step))) {
        return;
    }
    switch step {
        case 0u: { textureStore(level0, texel, vec4f(value)); }
        case 1u: { textureStore(level1, texel, vec4f(value)); }
        case 2u: { textureStore(level2, texel, vec4f(value)); }
        default: { textureStore(level3, texel, vec4f(value)); }
    }
}

// Stores this invocation's texel of the dispatch's first level, `value`, then halves the tile
// three times. Barriers stay in uniform control flow: every invocation runs every step.
fn reduceTile(local: vec2u, group: vec2u, value: f32) {
    farthest[local.y * kTile + local.x] = value;
    storeLevel(0u, group * kTile + local, value);
    var size = kTile;
    for (var step = 1u; step < 4u; step++) {
        size /= 2u;
        workgroupBarrier();
        let reduces = all(local < vec2u(size));
        var coarser = 0.0;
        if (reduces) {
            let child = local * 2u;
            let top = child.y * kTile + child.x;
            coarser = max(max(farthest[top], farthest[top + 1u]),
                        max(farthest[top + kTile], farthest[top + kTile + 1u]));
        }
        workgroupBarrier();
        if (reduces) {
            farthest[local.y * kTile + local.x] = coarser;
            storeLevel(step, group * size + local, coarser);
        }
    }
}

fn farthestDepthAt(pixel: vec2u) -> f32 {
    if (any(pixel >= reduction.depthSize)) {
        return 0.0;
    }
#if VISIBILITY_BUFFER
    let first = (pixel.y * reduction.depthSize.x + pixel.x) * reduction.samples;
    var deepest = 0.0;
    for (var sample = 0u; sample < reduction.samples; sample++) {
        let nearest = visibility[first + sample].y;
        deepest = max(deepest, select(bitcast<f32>(~nearest), 1.0, nearest == 0u));
    }
    return deepest;
#elif MULTISAMPLED
    var deepest = 0.0;
    for (var sample = 0u; sample < textureNumSamples(depth); sample++) {
        deepest = max(deepest, textureLoad(depth, pixel, i32(sample)));
    }
    return deepest;
#else
    return textureLoad(depth, pixel, 0);
#endif
}

@compute @workgroup_size(16, 16)
fn reduceDepth(@builtin(workgroup_id) group: vec3u,
               @builtin(local_invocation_id) local: vec3u) {
    let pixel = (group.xy * kTile + local.xy) * 2u;
    reduceTile(local.xy, group.xy,
               max(max(farthestDepthAt(pixel), farthestDepthAt(pixel + vec2u(1u, 0u))),
                   max(farthestDepthAt(pixel + vec2u(0u, 1u)), farthestDepthAt(pixel + 1u))));
}

fn finerTexel(texel: vec2u) -> f32 {
    if (any(texel >= levelSize(reduction.firstLevel - 1u))) {
        return 0.0;
    }
    return textureLoad(finer, texel, 0).r;
}

@compute @workgroup_size(16, 16)
fn reduceLevels(@builtin(workgroup_id) group: vec3u,
                @builtin(local_invocation_id) local: vec3u) {
    let child = (group.xy * kTile + local.xy) * 2u;
    reduceTile(local.xy, group.xy,
               max(max(finerTexel(child), finerTexel(child + vec2u(1u, 0u))),
                   max(finerTexel(child + vec2u(0u, 1u)), finerTexel(child + 1u))));
}
