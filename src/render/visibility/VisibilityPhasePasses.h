#pragma once

#include <webgpu/webgpu_cpp.h>

#include "gpu/GpuTimer.h"

namespace encore::render {

// The compute work of a raster phase or of the shading: one pass (timed as one under a GPU
// timer), or, where the timer asks for step detail, a timed pass per step, so that the timings
// say where the time goes (a step sets all its bindings itself).
class VisibilityPhasePasses {
  public:
    VisibilityPhasePasses(const wgpu::CommandEncoder& commands,
                          gpu::GpuTimer* timer,
                          const char* label)
        : mCommands(commands), mTimer(timer), mLabel(label) {}
    ~VisibilityPhasePasses() {
        if (mPass) {
            mPass.End();
        }
    }
    VisibilityPhasePasses(const VisibilityPhasePasses&) = delete;
    VisibilityPhasePasses& operator=(const VisibilityPhasePasses&) = delete;

    // The pass for the step named `timerLabel`.
    const wgpu::ComputePassEncoder& step(const char* timerLabel) {
        const bool steps = mTimer && mTimer->stepDetail();
        if (mPass && !steps) {
            return mPass;
        }
        if (mPass) {
            mPass.End();
        }
        wgpu::ComputePassDescriptor descriptor{};
        descriptor.label = mLabel;
        descriptor.timestampWrites =
            mTimer ? mTimer->nextPass(steps ? timerLabel : mLabel) : nullptr;
        mPass = mCommands.BeginComputePass(&descriptor);
        return mPass;
    }

  private:
    const wgpu::CommandEncoder& mCommands;
    gpu::GpuTimer* mTimer;
    const char* mLabel;
    wgpu::ComputePassEncoder mPass;
};

}  // namespace encore::render
