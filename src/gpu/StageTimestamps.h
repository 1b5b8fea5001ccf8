#pragma once

// GPU time summed by stage over many submissions, without waiting for the GPU: for a pipeline
// that submits work continuously (encore batch) and wants to know where the GPU's time goes
// (mip generation, scene passes, tone mapping, read-back copies), where gpu::GpuTimer times one
// frame and waits for it.
//
// Passes get timestamp writes from pass(); commands outside passes (copies) are timed by
// timeCommands() between two empty compute passes whose end timestamps say when everything
// recorded before them had finished. flush() resolves what was written since the last flush in a
// submission of its own and maps the result asynchronously; the durations reach the totals once
// the mapping finishes, seen at a later flush() or at finish(). Timestamps need the device's
// TimestampQuery feature (gpu::ContextOptions::timestamps, which also turns off Dawn's ~65 us
// quantization).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "encore/gpu/Context.h"

namespace encore::gpu {

struct StageTime {
    double milliseconds = 0.0;  // Summed over the stage's timed passes or commands.
    std::uint64_t timed = 0;    // Passes (or timeCommands calls) counted.
    std::uint64_t untimed = 0;  // Left untimed because the query set was full before a flush.
};

class StageTimestamps {
  public:
    // nullopt when the device lacks TimestampQuery. Stages are 0 .. stageCount - 1, named by the
    // caller. The context must outlive this object.
    static std::optional<StageTimestamps> create(Context& context, std::uint32_t stageCount);

    StageTimestamps(StageTimestamps&&) noexcept;
    StageTimestamps& operator=(StageTimestamps&&) noexcept;
    ~StageTimestamps();

    // The timestampWrites of a pass of `stage`, valid until the next call; nullptr when the
    // query set holds no more until the next flush (the pass then goes untimed).
    const wgpu::PassTimestampWrites* pass(std::uint32_t stage);

    // Calls `record` to add commands to `encoder` and times them as `stage`: the interval from
    // the end of everything recorded before them to the end of themselves.
    void timeCommands(const wgpu::CommandEncoder& encoder,
                      std::uint32_t stage,
                      const std::function<void()>& record);

    // Resolves every timestamp written since the last flush and starts reading it back. Call
    // only once every command buffer holding those passes has been submitted. Also adds the
    // reads that have finished since to the totals.
    void flush();
    // Flushes and waits for every read: the totals then cover everything timed.
    void finish();

    // Per stage, as far as reads have finished.
    const std::vector<StageTime>& totals() const { return mTotals; }

  private:
    struct Read;
    StageTimestamps() = default;
    // Adds finished reads to the totals; with `wait`, waits for all of them.
    void collect(bool wait);

    Context* mContext = nullptr;
    wgpu::QuerySet mQueries;
    std::uint32_t mQueryCount = 0;
    std::uint32_t mNextQuery = 0;
    // Which stage each pair of queries since the last flush times.
    std::vector<std::uint32_t> mPairStages;
    wgpu::PassTimestampWrites mWrites{};
    std::vector<StageTime> mTotals;
    std::deque<std::unique_ptr<Read>> mReads;  // In flight, oldest first.
    std::vector<std::unique_ptr<Read>> mFreeReads;
};

}  // namespace encore::gpu
