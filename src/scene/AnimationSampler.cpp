// Sampling one animation sampler at a time t (glTF 2.0, appendix C "Interpolation"). Keys are
// found through a cursor that remembers the last interval, so playing forward costs O(1) per
// channel; anything else falls back to a binary search. Nothing here allocates.

#include <algorithm>
#include <cmath>

#include "encore/scene/SceneData.h"

namespace encore::scene {
namespace {

// The k such that times[k] <= time < times[k + 1]; requires times.front() < time < times.back().
std::uint32_t findInterval(const std::vector<float>& times, float time, SamplerCursor& cursor) {
    const auto last = static_cast<std::uint32_t>(times.size() - 1);
    const std::uint32_t k = cursor.key;
    if (k < last && times[k] <= time) {
        if (time < times[k + 1]) {
            return k;
        }
        if (k + 2 <= last && time < times[k + 2]) {  // The next interval: playing forward.
            cursor.key = k + 1;
            return k + 1;
        }
    }
    const auto next = std::upper_bound(times.begin(), times.end(), time);
    const auto found = static_cast<std::uint32_t>(std::clamp<std::ptrdiff_t>(
        next - times.begin() - 1, 0, static_cast<std::ptrdiff_t>(last) - 1));
    cursor.key = found;
    return found;
}

void copyValue(const float* from, std::span<float> out, std::uint32_t components) {
    std::copy(from, from + components, out.begin());
}

// Shortest-path spherical interpolation of two x, y, z, w quaternions (normalised later).
void slerp(const float* a, const float* b, float u, std::span<float> out) {
    float dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const float sign = dot < 0.0f ? -1.0f : 1.0f;
    dot = std::abs(dot);
    float wa = 1.0f - u;
    float wb = u;
    // Nearly parallel quaternions: sin(theta) vanishes, and linear interpolation is exact enough.
    if (dot < 0.9995f) {
        const float theta = std::acos(std::min(dot, 1.0f));
        const float sine = std::sin(theta);
        wa = std::sin((1.0f - u) * theta) / sine;
        wb = std::sin(u * theta) / sine;
    }
    for (int c = 0; c < 4; ++c) {
        out[c] = wa * a[c] + sign * wb * b[c];
    }
}

void normalizeQuaternion(std::span<float> q) {
    const float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (length > 0.0f && std::isfinite(length)) {
        for (int c = 0; c < 4; ++c) {
            q[c] /= length;
        }
    } else {
        q[0] = q[1] = q[2] = 0.0f;
        q[3] = 1.0f;
    }
}

}  // namespace

void sampleAnimation(const AnimationSampler& sampler,
                     float time,
                     bool quaternion,
                     SamplerCursor& cursor,
                     std::span<float> out) {
    const std::uint32_t n = sampler.components;
    const std::vector<float>& times = sampler.times;
    if (n == 0 || times.empty() || out.size() < n) {
        return;
    }
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const std::size_t stride = cubic ? 3 * std::size_t(n) : n;  // Floats per key.
    const std::size_t valueOffset = cubic ? n : 0;              // The value after the in-tangent.
    const float* values = sampler.values.data();
    auto value = [&](std::size_t key) { return values + key * stride + valueOffset; };

    const std::size_t keys = times.size();
    if (keys == 1 || !(time > times.front())) {  // Also NaN: the first value.
        copyValue(value(0), out, n);
    } else if (time >= times.back()) {
        copyValue(value(keys - 1), out, n);
    } else {
        const std::uint32_t k = findInterval(times, time, cursor);
        const float t0 = times[k];
        const float interval = times[k + 1] - t0;
        const float u = std::clamp((time - t0) / interval, 0.0f, 1.0f);
        switch (sampler.interpolation) {
            case Interpolation::Step:
                copyValue(value(k), out, n);
                break;
            case Interpolation::Linear:
                if (quaternion && n == 4) {
                    slerp(value(k), value(k + 1), u, out);
                } else {
                    const float* a = value(k);
                    const float* b = value(k + 1);
                    for (std::uint32_t c = 0; c < n; ++c) {
                        out[c] = a[c] + (b[c] - a[c]) * u;
                    }
                }
                break;
            case Interpolation::CubicSpline: {
                // Hermite basis; tangents are per second, so they scale with the interval.
                const float u2 = u * u;
                const float u3 = u2 * u;
                const float h00 = 2.0f * u3 - 3.0f * u2 + 1.0f;
                const float h10 = u3 - 2.0f * u2 + u;
                const float h01 = -2.0f * u3 + 3.0f * u2;
                const float h11 = u3 - u2;
                const float* p0 = value(k);
                const float* m0 = values + k * stride + 2 * std::size_t(n);  // Out-tangent of k.
                const float* p1 = value(k + 1);
                const float* m1 = values + (k + 1) * stride;  // In-tangent of k + 1.
                for (std::uint32_t c = 0; c < n; ++c) {
                    out[c] =
                        h00 * p0[c] + h10 * interval * m0[c] + h01 * p1[c] + h11 * interval * m1[c];
                }
                break;
            }
        }
    }
    if (quaternion && n == 4) {
        normalizeQuaternion(out);
    }
}

}  // namespace encore::scene
