// The compute raster's edge functions (visibility_raster.wgsl): vertices and samples in fixed
// point (1/256 pixel) relative to a triangle's first pixel, in 32 bits up to kNarrowPixels
// across and exactly in 64 bits beyond, and the top-left fill rule the hardware applies.

// The edge function of a -> b at p (twice the signed area), in fixed point.
fn edge(a: vec2i, b: vec2i, p: vec2i) -> i32 {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Up to this many pixels across, the fixed-point edge functions (relative to the triangle's
// first pixel) stay within 32 bits; larger triangles evaluate them in 64 bits (wideEdge).
const kNarrowPixels = 112.0;

// A 64-bit two's complement integer as (low word, high word).
fn negateWide(v: vec2u) -> vec2u {
    let low = ~v.x + 1u;
    return vec2u(low, ~v.y + select(0u, 1u, low == 0u));
}

// a * b exactly, for |a| and |b| below 2^24 (WGSL has no 64-bit integers).
fn multiplyWide(a: i32, b: i32) -> vec2u {
    let ua = u32(abs(a));
    let ub = u32(abs(b));
    let low = (ua & 0xffffu) * (ub & 0xffffu);
    let middle = (ua & 0xffffu) * (ub >> 16u) + (ua >> 16u) * (ub & 0xffffu);  // Below 2^25.
    let sum = low + (middle << 16u);
    let product = vec2u(sum, (ua >> 16u) * (ub >> 16u) + (middle >> 16u) + select(0u, 1u, sum < low));
    return select(product, negateWide(product), (a < 0) != (b < 0));
}

// edge() in 64 bits: vertices and samples within 2^22 of each other (kMaxWorkgroupPixels).
fn wideEdge(a: vec2i, b: vec2i, p: vec2i) -> vec2u {
    let plus = multiplyWide(b.x - a.x, p.y - a.y);
    let minus = multiplyWide(b.y - a.y, p.x - a.x);
    return vec2u(plus.x - minus.x, plus.y - minus.y - select(0u, 1u, plus.x < minus.x));
}

// The sign of a wide value: -1, 0 or 1.
fn wideSign(v: vec2u) -> i32 {
    if (i32(v.y) < 0) {
        return -1;
    }
    return select(1, 0, v.x == 0u && v.y == 0u);
}

// Whether edge + bias >= 0 (bias -1 or 0), in 64 bits.
fn wideInside(a: vec2i, b: vec2i, p: vec2i, bias: i32) -> bool {
    return wideSign(wideEdge(a, b, p)) + bias >= 0;
}

// With the triangle wound so that inside is positive (clockwise on the y-down screen): top edges
// run right along a row, left edges run up. Pixel centres on such an edge are inside, on the
// other edges outside, so a pixel shared by two triangles belongs to one.
fn topLeftBias(a: vec2i, b: vec2i) -> i32 {
    let d = b - a;
    return select(-1, 0, (d.y == 0 && d.x > 0) || d.y < 0);
}
