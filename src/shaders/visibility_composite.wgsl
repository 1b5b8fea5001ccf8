// The visibility strategy's last step. Inside the frame's render pass: a fullscreen triangle
// that copies each covered sample's shaded colour into the target and its visibility-buffer
// depth into the depth attachment (for the background, the hardware-drawn rest of the scene and
// blended geometry after it); uncovered samples are discarded. It runs per sample
// (sample_index): with MULTISAMPLED, each of a pixel's four samples takes the colour its
// triangle was shaded with (at the first sample that triangle covers, visibility_bins.wgsl) and
// its own depth, and the target's resolve averages them as it averages hardware-drawn samples.
// When nothing is drawn after it (no MASK, BLEND, skinned or transmissive geometry: no later
// depth test), pixelMain runs once per pixel instead, a quarter of the fragments at four
// samples, and writes no depth: the sum of the covered samples' colours over the sample count,
// blended over the background (premultiplied: the compute path's surfaces are opaque, so its
// alpha is the covered fraction). Every sample of the pixel then holds what the resolve would
// average them to, which keeps the multisampled target compressed (on the H100 writing chosen
// samples, sample_mask, cost three times a one-sample target's pass).
// With a plain background colour, composeMain does pixelMain's work in compute instead, for
// every pixel (uncovered ones take the background), straight into the target through a storage
// view (FramePasses::composeFrame, visibility_composed.wgsl): no render pass at all, whose every
// fragment costs the H100's few graphics units about 0.3 ns. At one sample the shading and the
// binning write the target themselves (COMPOSED in
// visibility_shade.wgsl and visibility_bins.wgsl), and composeMain does not run.
#include "visibility_samples.wgsl"
#include "visibility_composed.wgsl"
#include "fullscreen_triangle.wgsl"

#if MULTISAMPLED
const kSamples = 4u;
#else
const kSamples = 1u;
#endif

@group(0) @binding(0) var<storage, read> visibility: array<vec2u>;
@group(0) @binding(1) var shaded: texture_2d_array<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4f {
    return fullscreenPosition(vertex);
}

// The sample whose shaded colour triangle `id`, covering `sample` of the pixel whose entries start
// at `first`, takes: its first sample there (where visibility_bins.wgsl lists it).
fn shadedSampleOf(first: u32, sample: u32, id: u32) -> u32 {
    for (var earlier = 0u; earlier < sample; earlier++) {
        let other = visibility[first + earlier];
        if (other.y != 0u && other.x == id) {
            return earlier;
        }
    }
    return sample;
}

struct FragmentOutput {
    @location(0) color: vec4f,
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fragmentMain(@builtin(position) position: vec4f, @builtin(sample_index) sample: u32)
    -> FragmentOutput {
    let pixel = vec2u(position.xy);
    let width = textureDimensions(shaded).x;
    let first = (pixel.y * width + pixel.x) * kSamples;
    let key = visibility[first + sample];
    if (key.y == 0u) {
        discard;
    }
    var output: FragmentOutput;
    output.color = textureLoad(shaded, pixel, shadedSampleOf(first, sample, key.x), 0);
    output.depth = bitcast<f32>(~key.y);
    return output;
}

// The covered samples of `pixel` averaged over the sample count: the sum of their colours (each
// triangle's colour loaded once, weighted by the samples it covers) over kSamples, so that alpha
// is the covered fraction (premultiplied). `covered`: whether any sample is.
struct PixelColor {
    color: vec4f,
    covered: bool,
}

fn pixelColor(pixel: vec2u) -> PixelColor {
    let width = textureDimensions(shaded).x;
    let first = (pixel.y * width + pixel.x) * kSamples;
    // Per sample: how many covered samples take the colour shaded there (its triangle's first).
    var weights: array<f32, kSamples>;
    var result: PixelColor;
    for (var sample = 0u; sample < kSamples; sample++) {
        let key = visibility[first + sample];
        if (key.y != 0u) {
            result.covered = true;
            weights[shadedSampleOf(first, sample, key.x)] += 1.0;
        }
    }
    var sum = vec4f(0.0);
    for (var sample = 0u; sample < kSamples; sample++) {
        if (weights[sample] > 0.0) {
            sum += weights[sample] * textureLoad(shaded, pixel, sample, 0);
        }
    }
    result.color = sum / f32(kSamples);
    return result;
}

@fragment
fn pixelMain(@builtin(position) position: vec4f) -> @location(0) vec4f {
    let pixel = pixelColor(vec2u(position.xy));
    if (!pixel.covered) {
        discard;
    }
    return pixel.color;
}

@group(0) @binding(2) var composedFrame: ComposedFrame;
@group(0) @binding(3) var<uniform> composition: Composition;

@compute @workgroup_size(8, 8)
fn composeMain(@builtin(global_invocation_id) id: vec3u) {
    if (any(id.xy >= textureDimensions(shaded))) {  // The target's size.
        return;
    }
    // pixelMain's colour blended premultiplied over the background, as its pipeline blends.
    storeComposed(id.xy, pixelColor(id.xy).color);
}
