#pragma once

// Per-frame measurements shared by every benchmark (strategies and the Animometer scene).

#include <cstdint>
#include <optional>
#include <vector>

namespace encore::render {

// One measured frame. CPU times are wall-clock on the calling thread; gpuMilliseconds comes
// from timestamp queries around the frame's passes when the device supports them.
struct FrameTiming {
    double encodeMilliseconds = 0.0;  // Recording: command encoder, passes, Finish.
    double submitMilliseconds = 0.0;  // Queue::Submit (Dawn records the Vulkan commands here).
    std::optional<double> gpuMilliseconds;

    double cpuMilliseconds() const { return encodeMilliseconds + submitMilliseconds; }
};

// Median and 95th percentile of a series.
struct Percentiles {
    double median = 0.0;
    double p95 = 0.0;

    static Percentiles of(std::vector<double> values);
};

}  // namespace encore::render
