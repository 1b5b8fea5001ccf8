// The frame composed in compute (FramePasses::composeFrame): the target's scene colour written by
// the includer through `composedFrame`, a write-only storage view of the target
// (RenderTarget::sceneStorageView): no copy afterwards. HALF_OUTPUT: RGBA16Float (HDR
// targets); otherwise the RGBA8 bytes of the target's sRGB texture, encoded here as its sRGB
// views encode what a render pass draws.

struct Composition {
    background: vec4f,  // Linear: the scene pass's clear colour.
}

#if HALF_OUTPUT
alias ComposedFrame = texture_storage_2d<rgba16float, write>;
#else
alias ComposedFrame = texture_storage_2d<rgba8unorm, write>;
#endif

// The sRGB transfer function, as an sRGB target encodes a linear colour it is given.
fn srgbEncoded(linear: vec3f) -> vec3f {
    let c = clamp(linear, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3f(0.0031308));
}

// `color` (premultiplied) blended over the background into `pixel` of the target, as the
// render-pass composite's pipeline blends it.
fn storeComposed(pixel: vec2u, color: vec4f) {
    let blended = color + (1.0 - color.a) * composition.background;
#if HALF_OUTPUT
    textureStore(composedFrame, pixel, blended);
#else
    textureStore(composedFrame, pixel, vec4f(srgbEncoded(blended.rgb), blended.a));
#endif
}
