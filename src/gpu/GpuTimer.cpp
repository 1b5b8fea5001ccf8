#include "gpu/GpuTimer.h"

#include <algorithm>
#include <vector>

namespace encore::gpu {

std::optional<GpuTimer> GpuTimer::create(const Context& context, std::uint32_t maxPasses) {
    if (!context.hasFeature(wgpu::FeatureName::TimestampQuery)) {
        return std::nullopt;
    }
    GpuTimer timer;
    timer.mMaxPasses = std::clamp<std::uint32_t>(maxPasses, 1, std::size(timer.mWrites));
    const std::uint32_t queryCount = timer.mMaxPasses * 2 + 1;  // And the frame's end.
    wgpu::QuerySetDescriptor queries{};
    queries.label = "pass timestamps";
    queries.type = wgpu::QueryType::Timestamp;
    queries.count = queryCount;
    timer.mQueries = context.device().CreateQuerySet(&queries);
    wgpu::BufferDescriptor resolved{};
    resolved.label = "resolved timestamps";
    resolved.size = std::uint64_t(queryCount) * 8;
    resolved.usage = wgpu::BufferUsage::QueryResolve | wgpu::BufferUsage::CopySrc;
    timer.mResolved = context.device().CreateBuffer(&resolved);
    wgpu::BufferDescriptor staging{};
    staging.label = "timestamp readback";
    staging.size = resolved.size;
    staging.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
    timer.mStaging = context.device().CreateBuffer(&staging);
    return timer;
}

const wgpu::PassTimestampWrites* GpuTimer::nextPass(std::string_view label) {
    if (mPasses >= mMaxPasses) {
        return nullptr;
    }
    mLabels[mPasses] = label;
    wgpu::PassTimestampWrites& writes = mWrites[mPasses];
    writes.querySet = mQueries;
    writes.beginningOfPassWriteIndex = mPasses * 2;
    writes.endOfPassWriteIndex = mPasses * 2 + 1;
    ++mPasses;
    return &writes;
}

void GpuTimer::resolve(const wgpu::CommandEncoder& commands) {
    if (mPasses == 0) {
        return;
    }
    // The frame's end, after the last pass's: the end of an empty pass, which waits for every
    // command before it (a transfer after the last pass too).
    wgpu::PassTimestampWrites end{};
    end.querySet = mQueries;
    end.endOfPassWriteIndex = mPasses * 2;
    wgpu::ComputePassDescriptor marker{};
    marker.label = "frame end timestamp";
    marker.timestampWrites = &end;
    commands.BeginComputePass(&marker).End();
    commands.ResolveQuerySet(mQueries, 0, mPasses * 2 + 1, mResolved, 0);
    commands.CopyBufferToBuffer(mResolved, 0, mStaging, 0, std::uint64_t(mPasses) * 16 + 8);
    mResolvedThisFrame = true;
}

std::optional<double> GpuTimer::read(Context& context) {
    const std::uint32_t passes = mPasses;
    mPasses = 0;
    mLastPasses.clear();
    mLastSpan.reset();
    if (!mResolvedThisFrame || passes == 0) {
        return std::nullopt;
    }
    mResolvedThisFrame = false;
    const std::uint64_t size = std::uint64_t(passes) * 16 + 8;
    bool mapped = false;
    context.wait(mStaging.MapAsync(wgpu::MapMode::Read, 0, size, wgpu::CallbackMode::WaitAnyOnly,
                                   [&](wgpu::MapAsyncStatus status, wgpu::StringView) {
                                       mapped = status == wgpu::MapAsyncStatus::Success;
                                   }));
    if (!mapped) {
        return std::nullopt;
    }
    const auto* ticks = static_cast<const std::uint64_t*>(mStaging.GetConstMappedRange(0, size));
    double nanoseconds = 0.0;
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        const std::uint64_t begin = ticks[pass * 2];
        const std::uint64_t end = ticks[pass * 2 + 1];
        const double passNanoseconds = end > begin ? double(end - begin) : 0.0;
        nanoseconds += passNanoseconds;
        mLastPasses.push_back({std::string(mLabels[pass]), passNanoseconds / 1e6});
    }
    const std::uint64_t first = ticks[0];
    const std::uint64_t last = ticks[passes * 2];
    mLastSpan = last > first ? double(last - first) / 1e6 : 0.0;
    mStaging.Unmap();
    return nanoseconds / 1e6;
}

}  // namespace encore::gpu
