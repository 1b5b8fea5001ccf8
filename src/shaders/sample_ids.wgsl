// Segmentation ids from one sample of a multisampled frame (render/SampleIdPass.h). The resolve
// averages a pixel's samples, so where two objects (or an object and the background) share a
// pixel it writes an id that neither has. This pass reads sample 0 of the multisampled texture
// and writes its id into the resolved texture's two id channels (write mask), every other
// channel keeping the resolve's average. The pipeline multiplies the id by the resolved texel's
// alpha (blend factor dst-alpha): the ids stay premultiplied by coverage, as everything that
// reads them expects, and dividing by that coverage gives back the integer id.

#include "fullscreen_triangle.wgsl"

@group(0) @binding(0) var multisampled: texture_multisampled_2d<f32>;

@vertex
fn vertexMain(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
    return fullscreenPosition(index);
}

// The id at sample 0 from its two channels (premultiplied by the sample's alpha): 0 where the
// sample is less than half covered, as the readers treat a pixel.
fn sampleId(position: vec4f, first: u32) -> vec2f {
    let texel = textureLoad(multisampled, vec2i(position.xy), 0);
    if (!(texel.a >= 0.5)) {
        return vec2f(0.0);
    }
    return round(vec2f(texel[first], texel[first + 1u]) / texel.a);
}

// A frame drawn through a segmentation channel: R = id % 256, G = id / 256.
@fragment
fn channelIds(@builtin(position) position: vec4f) -> @location(0) vec4f {
    return vec4f(sampleId(position, 0u), 0.0, 0.0);
}

// The DepthAndId pass target: R depth, G = id % 256, B = id / 256.
@fragment
fn passTargetIds(@builtin(position) position: vec4f) -> @location(0) vec4f {
    return vec4f(0.0, sampleId(position, 1u), 0.0);
}
