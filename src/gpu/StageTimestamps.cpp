#include "gpu/StageTimestamps.h"

namespace encore::gpu {

namespace {
// Pairs of timestamps between two flushes, at most: a batch flushes after every model, whose
// mip levels and views need a few hundred at most. Passes past it go untimed (and are counted).
constexpr std::uint32_t kQueryCount = 4096;
constexpr std::uint64_t kTimestampBytes = 8;
}  // namespace

struct StageTimestamps::Read {
    wgpu::Buffer resolved;  // QueryResolve | CopySrc.
    wgpu::Buffer staging;   // MapRead.
    wgpu::Future future;
    std::vector<std::uint32_t> pairStages;
    // Set by the map callback, which runs inside Context::wait (WaitAnyOnly).
    bool mapped = false;
};

StageTimestamps::StageTimestamps(StageTimestamps&&) noexcept = default;
StageTimestamps& StageTimestamps::operator=(StageTimestamps&&) noexcept = default;

StageTimestamps::~StageTimestamps() {
    // The map callbacks refer to the reads: let them run before the reads go.
    if (mContext) {
        for (const auto& read : mReads) {
            mContext->wait(read->future);
        }
    }
}

std::optional<StageTimestamps> StageTimestamps::create(Context& context, std::uint32_t stageCount) {
    if (!context.hasFeature(wgpu::FeatureName::TimestampQuery)) {
        return std::nullopt;
    }
    StageTimestamps timestamps;
    timestamps.mContext = &context;
    timestamps.mQueryCount = kQueryCount;
    wgpu::QuerySetDescriptor queries{};
    queries.label = "stage timestamps";
    queries.type = wgpu::QueryType::Timestamp;
    queries.count = kQueryCount;
    timestamps.mQueries = context.device().CreateQuerySet(&queries);
    timestamps.mTotals.resize(stageCount);
    return timestamps;
}

const wgpu::PassTimestampWrites* StageTimestamps::pass(std::uint32_t stage) {
    if (mNextQuery + 2 > mQueryCount) {
        ++mTotals[stage].untimed;
        return nullptr;
    }
    mWrites = {};
    mWrites.querySet = mQueries;
    mWrites.beginningOfPassWriteIndex = mNextQuery;
    mWrites.endOfPassWriteIndex = mNextQuery + 1;
    mNextQuery += 2;
    mPairStages.push_back(stage);
    return &mWrites;
}

void StageTimestamps::timeCommands(const wgpu::CommandEncoder& encoder,
                                   std::uint32_t stage,
                                   const std::function<void()>& record) {
    if (mNextQuery + 2 > mQueryCount) {
        ++mTotals[stage].untimed;
        record();
        return;
    }
    // An empty compute pass's end timestamp is taken once the commands before it have finished
    // (Vulkan's bottom of pipe): one such marker before the commands and one after them.
    const auto marker = [&](std::uint32_t query) {
        wgpu::PassTimestampWrites writes{};
        writes.querySet = mQueries;
        writes.endOfPassWriteIndex = query;
        wgpu::ComputePassDescriptor descriptor{};
        descriptor.label = "timestamp marker";
        descriptor.timestampWrites = &writes;
        encoder.BeginComputePass(&descriptor).End();
    };
    const std::uint32_t first = mNextQuery;
    mNextQuery += 2;
    mPairStages.push_back(stage);
    marker(first);
    record();
    marker(first + 1);
}

void StageTimestamps::flush() {
    collect(false);
    if (mNextQuery == 0) {
        return;
    }
    std::unique_ptr<Read> read;
    if (!mFreeReads.empty()) {
        read = std::move(mFreeReads.back());
        mFreeReads.pop_back();
    } else {
        read = std::make_unique<Read>();
        const std::uint64_t size = std::uint64_t(mQueryCount) * kTimestampBytes;
        wgpu::BufferDescriptor resolved{};
        resolved.label = "stage timestamps (resolved)";
        resolved.size = size;
        resolved.usage = wgpu::BufferUsage::QueryResolve | wgpu::BufferUsage::CopySrc;
        read->resolved = mContext->device().CreateBuffer(&resolved);
        wgpu::BufferDescriptor staging{};
        staging.label = "stage timestamps (read-back)";
        staging.size = size;
        staging.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
        read->staging = mContext->device().CreateBuffer(&staging);
    }
    const std::uint64_t bytes = std::uint64_t(mNextQuery) * kTimestampBytes;
    wgpu::CommandEncoder encoder = mContext->device().CreateCommandEncoder();
    encoder.ResolveQuerySet(mQueries, 0, mNextQuery, read->resolved, 0);
    encoder.CopyBufferToBuffer(read->resolved, 0, read->staging, 0, bytes);
    wgpu::CommandBuffer commands = encoder.Finish();
    mContext->queue().Submit(1, &commands);
    // The queue runs the resolve before anything submitted later: the queries may be written
    // again from the start.
    mNextQuery = 0;
    read->pairStages = std::move(mPairStages);
    mPairStages.clear();
    read->mapped = false;
    Read* target = read.get();
    read->future =
        read->staging.MapAsync(wgpu::MapMode::Read, 0, bytes, wgpu::CallbackMode::WaitAnyOnly,
                               [target](wgpu::MapAsyncStatus status, wgpu::StringView) {
                                   target->mapped = status == wgpu::MapAsyncStatus::Success;
                               });
    mReads.push_back(std::move(read));
}

void StageTimestamps::finish() {
    flush();
    collect(true);
}

void StageTimestamps::collect(bool wait) {
    while (!mReads.empty()) {
        Read& read = *mReads.front();
        if (!mContext->wait(read.future, wait ? UINT64_MAX : 0)) {
            return;  // Reads finish in order: the later ones are not done either.
        }
        if (read.mapped) {
            const std::uint64_t bytes = read.pairStages.size() * 2 * kTimestampBytes;
            const auto* ticks =
                static_cast<const std::uint64_t*>(read.staging.GetConstMappedRange(0, bytes));
            for (std::size_t pair = 0; pair < read.pairStages.size(); ++pair) {
                const std::uint64_t begin = ticks[pair * 2];
                const std::uint64_t end = ticks[pair * 2 + 1];
                StageTime& total = mTotals[read.pairStages[pair]];
                // Dawn converts ticks to nanoseconds. A pair out of order (a driver that
                // reorders markers) counts as zero rather than wrapping around.
                total.milliseconds += end > begin ? double(end - begin) / 1e6 : 0.0;
                ++total.timed;
            }
            read.staging.Unmap();
        }
        mFreeReads.push_back(std::move(mReads.front()));
        mReads.pop_front();
    }
}

}  // namespace encore::gpu
