#pragma once

// One command buffer, encoded by a callback and submitted, with the CPU time of each step and,
// given a GpuTimer, the GPU time of the passes the callback timed with it: the frame loop of the
// renderer and the animometer.

#include <webgpu/webgpu_cpp.h>

#include <functional>
#include <optional>

#include "encore/gpu/Context.h"
#include "gpu/GpuTimer.h"

namespace encore::gpu {

struct SubmitTiming {
    double encodeMilliseconds = 0.0;        // Creating the encoder, the callback, resolve, Finish.
    double submitMilliseconds = 0.0;        // Queue::Submit.
    std::optional<double> gpuMilliseconds;  // GpuTimer::read: with a timer that timed a pass.
};

// Creates a command encoder and calls `encode` with it; the callback gives its passes
// timer->nextPass() as their timestampWrites. Then resolves the timer's queries, finishes, submits
// and, with a timer, waits for the GPU to read its result (GpuTimer::read). Without a timer
// nothing waits.
SubmitTiming submitTimed(Context& context,
                         GpuTimer* timer,
                         const std::function<void(const wgpu::CommandEncoder&)>& encode);

}  // namespace encore::gpu
