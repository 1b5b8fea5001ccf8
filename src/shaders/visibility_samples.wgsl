// The visibility buffer's samples (VisibilityParams.samples: 1, or 4 with `--samples 4`): where
// each lies in its pixel, and where the shading pass leaves each sample's colour.

// Sample `sample`'s position in its pixel, in the compute raster's fixed point (1/256 pixel):
// the centre at one sample; at four, the standard pattern of Vulkan and D3D, (6, 2), (14, 6),
// (2, 10) and (10, 14) sixteenths, which the hardware's multisampling uses, so that edges fall
// on the same samples.
fn samplePosition(samples: u32, sample: u32) -> vec2i {
    if (samples == 1u) {
        return vec2i(128);
    }
    let positions =
        array<vec2i, 4>(vec2i(96, 32), vec2i(224, 96), vec2i(32, 160), vec2i(160, 224));
    return positions[sample & 3u];
}

// The shaded colour texture is an array of one layer per sample, each the target's size: a
// wide multi-view target (encore batch's strips) stays within maxTextureDimension2D.
