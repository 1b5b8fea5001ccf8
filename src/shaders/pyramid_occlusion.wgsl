// The occlusion test against a depth pyramid (depth_pyramid.wgsl), shared by GPU culling
// (culling.wgsl) and the visibility strategy (visibility_cull.wgsl): whether something no nearer
// than `nearestDepth` over the pixels [low, high] (continuous, in a `viewport`-sized target) lies
// behind the farthest depth drawn anywhere there.
fn pyramidHides(pyramid: texture_2d<f32>,
                viewport: vec2f,
                lowPixel: vec2f,
                highPixel: vec2f,
                nearestDepth: f32) -> bool {
    let lastPixel = viewport - vec2f(1.0);
    let low = clamp(lowPixel, vec2f(0.0), lastPixel);
    let high = clamp(highPixel, vec2f(0.0), lastPixel);
    // Level k's texels cover 2^(k+1) pixels a side (depth_pyramid.wgsl): at the level where that
    // is at least the extent, the pixels overlap at most 2x2 texels (more where they span more
    // than the last level's texels).
    let extent = max(high.x - low.x, high.y - low.y);
    let level = min(u32(max(ceil(log2(max(extent, 1.0))) - 1.0, 0.0)),
                    textureNumLevels(pyramid) - 1u);
    let texelPixels = 1u << (level + 1u);
    let lastTexel = (vec2u(viewport) + vec2u(texelPixels - 1u)) / texelPixels - vec2u(1u);
    let texelSize = f32(texelPixels);
    let first = min(vec2u(low / texelSize), lastTexel);
    let last = min(vec2u(high / texelSize), lastTexel);
    var farthest = 0.0;
    for (var y = first.y; y <= last.y; y++) {
        for (var x = first.x; x <= last.x; x++) {
            farthest = max(farthest, textureLoad(pyramid, vec2u(x, y), level).r);
        }
    }
    return nearestDepth > farthest;
}
