// The frame composed in compute (Strategy::composeFrame): a texel of the target's format per
// pixel in the includer's `composed` buffer, rows of `composition.rowTexels`, copied into the
// target afterwards. HALF_OUTPUT: RGBA16Float texels (HDR targets); otherwise RGBA8 bytes,
// sRGB-encoded as the sRGB target's hardware encodes.

struct Composition {
    background: vec4f,  // Linear: the scene pass's clear colour.
    rowTexels: u32,     // The composed buffer's row pitch (rows of 256-byte multiples).
}

// The sRGB transfer function, as an sRGB target encodes a linear colour it is given.
fn srgbEncoded(linear: vec3f) -> vec3f {
    let c = clamp(linear, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3f(0.0031308));
}

// `color` (premultiplied) blended over the background into the texel of `pixel`, as the
// render-pass composite's pipeline blends it.
fn storeComposed(pixel: vec2u, color: vec4f) {
    let blended = color + (1.0 - color.a) * composition.background;
    let texel = pixel.y * composition.rowTexels + pixel.x;
#if HALF_OUTPUT
    composed[texel * 2u] = pack2x16float(blended.rg);
    composed[texel * 2u + 1u] = pack2x16float(blended.ba);
#else
    composed[texel] = pack4x8unorm(vec4f(srgbEncoded(blended.rgb), blended.a));
#endif
}
