#pragma once

// glTF animations as the loader hands them out, and the interpolation of one sampler.
//
// The loader decodes every sampler once: key times become floats (checked finite and strictly
// increasing) and output values floats, normalised integers mapped as glTF says
// (max(c / 127, -1) for signed bytes, c / 65535 for unsigned shorts...). Channels name the node
// and the property they drive; a sampler's element width (`components`) always matches the path
// of every channel that uses it: 3 for translation and scale, 4 for rotation (x, y, z, w) and the
// number of morph targets of the node's mesh for weights. AnimationPlayer.h plays them.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "encore/scene/Ids.h"

namespace encore::scene {

enum class AnimationPath : std::uint8_t { Translation, Rotation, Scale, Weights };

enum class Interpolation : std::uint8_t {
    Step,         // The value of the key at or before t.
    Linear,       // Linear; rotations use shortest-path spherical interpolation.
    CubicSpline,  // Cubic Hermite with the file's tangents (scaled by the key interval).
};

std::string_view animationPathName(AnimationPath path);  // "translation"...
std::string_view interpolationName(Interpolation mode);  // "STEP", "LINEAR", "CUBICSPLINE"

struct AnimationSampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;  // Seconds; at least one, finite, strictly increasing.
    // Per key: `components` floats (STEP, LINEAR), or in-tangent, value, out-tangent, each
    // `components` floats (CUBICSPLINE), as glTF stores them.
    std::vector<float> values;
    std::uint32_t components = 0;
};

struct AnimationChannel {
    std::uint32_t sampler = 0;  // Index into Animation::samplers.
    NodeId node;                // Always valid.
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    // Channels whose target the loader cannot drive (no node, an unknown path, weights of a node
    // without morph targets) are left out, with a warning where glTF calls them invalid.
    std::vector<AnimationChannel> channels;
    // Seconds added to the playback time before this animation is sampled (and wrapped, when
    // looping): glTF has no such property, so Encore reads it from the animation's
    // `extras.encoreTimeOffset`. Many copies of one animated model can then share its keyframes
    // (same accessors) and still play out of step; viewers that ignore it play them in step.
    float timeOffset = 0.0f;
    float start = 0.0f;  // First key time over the channels' samplers (0 without channels).
    float end = 0.0f;    // Last key time: the animation's duration as players report it.
};

// Where a sampler was last evaluated; lets sequential evaluation skip the binary search.
// One cursor per (player, sampler); any value is valid (it is only a hint).
struct SamplerCursor {
    std::uint32_t key = 0;
};

// Evaluates `sampler` at `time` seconds into `out` (sampler.components floats; `out` must hold
// that many). Times before the first key give the first value, after the last key the last
// value. With `quaternion` (rotation channels, components == 4) LINEAR is a shortest-path slerp
// and the result of every mode is normalised (a zero quaternion becomes the identity). Never
// allocates.
void sampleAnimation(const AnimationSampler& sampler,
                     float time,
                     bool quaternion,
                     SamplerCursor& cursor,
                     std::span<float> out);

}  // namespace encore::scene
