#pragma once

// A value that a batch may vary from view to view or model to model: fixed (min == max), or
// drawn uniformly between min and max from the batch's seed (`--distance 1.5:2.2`).

namespace encore::batch {

struct ValueRange {
    float min = 0.0f;
    float max = 0.0f;

    constexpr ValueRange() = default;
    // A fixed value: options that took one number before still take it.
    constexpr ValueRange(float value) : min(value), max(value) {}  // NOLINT(google-explicit-*)
    constexpr ValueRange(float low, float high) : min(low), max(high) {}

    bool fixed() const { return min == max; }
    // min + unit (max - min), for unit in [0, 1): exactly min when fixed.
    float at(double unit) const {
        return fixed() ? min : float(double(min) + unit * (double(max) - double(min)));
    }

    bool operator==(const ValueRange&) const = default;
};

}  // namespace encore::batch
