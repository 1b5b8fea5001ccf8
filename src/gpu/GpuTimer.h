#pragma once

// GPU time of a frame's passes, from timestamp queries written at the beginning and end of each
// pass (the TimestampQuery feature; Context::create with timestamps = true requests it and
// disables Dawn's ~65 us timestamp quantization). The result sums every pass's duration.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "encore/gpu/Context.h"

namespace encore::gpu {

class GpuTimer {
  public:
    // nullopt when the device lacks TimestampQuery.
    static std::optional<GpuTimer> create(const Context& context, std::uint32_t maxPasses = 8);

    // Timestamp writes for the next pass of the current frame (nullptr once maxPasses were used:
    // the pass then goes untimed). `label` names the pass in lastPasses(); it must live until
    // read() (a string literal: nothing is copied while the frame is encoded).
    const wgpu::PassTimestampWrites* nextPass(std::string_view label = "pass");

    // Resolves this frame's queries; call on the frame's command encoder after its last command
    // (the span ends there).
    void resolve(const wgpu::CommandEncoder& commands);

    // After the frame's submit: waits for the results and returns the summed pass time in
    // milliseconds, then starts a new frame. nullopt when no pass was timed.
    std::optional<double> read(Context& context);

    // Whether a pass of several steps (the visibility strategy's phases) runs each step as a
    // timed pass of its own, to say where its time goes (off by default: the frame is timed as
    // it runs untimed). Each boundary added costs the frame its timestamps and a wait for the
    // step before: on the H100 the visibility strategy's city frame measured 0.334 ms with its
    // steps apart, 0.295 as it runs (docs/visibility-performance.md).
    void setStepDetail(bool on) { mStepDetail = on; }
    bool stepDetail() const { return mStepDetail; }

    // The passes the last read() summed, in the order they began, each with its label.
    struct TimedPass {
        std::string label;
        double milliseconds = 0.0;
    };
    const std::vector<TimedPass>& lastPasses() const { return mLastPasses; }
    // The last read() frame's span, in milliseconds: from the first pass's beginning to the end
    // of the frame's commands (resolve() ends an empty pass there, whose timestamp waits for
    // everything before it). Unlike the sum, it counts the transfers before, between and after
    // the passes (clears, copies) and the GPU's idle gaps between them.
    std::optional<double> lastSpan() const { return mLastSpan; }

  private:
    wgpu::QuerySet mQueries;
    wgpu::Buffer mResolved;
    wgpu::Buffer mStaging;
    wgpu::PassTimestampWrites mWrites[16];
    std::string_view mLabels[16];
    std::vector<TimedPass> mLastPasses;
    std::optional<double> mLastSpan;
    std::uint32_t mMaxPasses = 0;
    std::uint32_t mPasses = 0;
    bool mResolvedThisFrame = false;
    bool mStepDetail = false;
};

}  // namespace encore::gpu
