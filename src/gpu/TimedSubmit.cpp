#include "gpu/TimedSubmit.h"

#include <chrono>

#include "core/Elapsed.h"

namespace encore::gpu {

SubmitTiming submitTimed(Context& context,
                         GpuTimer* timer,
                         const std::function<void(const wgpu::CommandEncoder&)>& encode) {
    SubmitTiming timing;
    const auto encodeStart = std::chrono::steady_clock::now();
    const wgpu::CommandEncoder encoder = context.device().CreateCommandEncoder();
    encode(encoder);
    if (timer) {
        timer->resolve(encoder);
    }
    const wgpu::CommandBuffer commands = encoder.Finish();
    timing.encodeMilliseconds = millisecondsSince(encodeStart);

    const auto submitStart = std::chrono::steady_clock::now();
    context.queue().Submit(1, &commands);
    timing.submitMilliseconds = millisecondsSince(submitStart);
    if (timer) {
        timing.gpuMilliseconds = timer->read(context);
    }
    return timing;
}

}  // namespace encore::gpu
