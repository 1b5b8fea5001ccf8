#include "gpu/StagingBuffers.h"

#include <algorithm>
#include <bit>

namespace encore::gpu {

namespace {
constexpr std::uint64_t kSmallestBuffer = std::uint64_t{1} << 20;
}

StagingBuffers::StagingBuffers(Context& context, std::uint64_t keptBytes)
    : mContext(context), mDevice(context.device()), mKeptBytes(keptBytes) {}

StagingBuffers::~StagingBuffers() {
    if (mDevice.Get() != mContext.device().Get()) {
        return;  // Destroyed with the lost device: its futures may no longer be waited for.
    }
    for (const auto& remapping : mRemapping) {
        mContext.wait(remapping->future);
    }
}

void StagingBuffers::collect() {
    // Mappings finish in the order the GPU finishes the copies, which is the order of the
    // submits: stop at the first still pending.
    while (!mRemapping.empty() && mContext.wait(mRemapping.front()->future, 0)) {
        Remapping& done = *mRemapping.front();
        if (*done.mapped) {
            mFree.push_back(std::move(done.buffer));
        } else {
            mBytes -= done.buffer.GetSize();  // A lost device: let it go.
        }
        mRemapping.pop_front();
    }
}

wgpu::Buffer StagingBuffers::takeFree(std::uint64_t size) {
    // The smallest kept buffer that is large enough.
    auto best = mFree.end();
    for (auto it = mFree.begin(); it != mFree.end(); ++it) {
        if (it->GetSize() >= size && (best == mFree.end() || it->GetSize() < best->GetSize())) {
            best = it;
        }
    }
    if (best == mFree.end()) {
        return {};
    }
    wgpu::Buffer buffer = std::move(*best);
    mFree.erase(best);
    mBytes -= buffer.GetSize();
    return buffer;
}

wgpu::Buffer StagingBuffers::acquire(std::uint64_t size) {
    collect();
    if (wgpu::Buffer free = takeFree(size)) {
        return free;
    }
    // A buffer being mapped again is free once the GPU is past the copy out of it, which was
    // submitted: waiting for it waits for the GPU, as a device thread ahead of the GPU does
    // anyway, and a batch in steady state then creates no buffer however the GPU keeps pace.
    const bool deviceAlive = mDevice.Get() == mContext.device().Get();
    for (auto it = mRemapping.begin(); deviceAlive && it != mRemapping.end(); ++it) {
        if ((*it)->buffer.GetSize() < size) {
            continue;
        }
        std::unique_ptr<Remapping> remapping = std::move(*it);
        mRemapping.erase(it);
        mContext.wait(remapping->future);
        mBytes -= remapping->buffer.GetSize();
        if (*remapping->mapped) {
            return std::move(remapping->buffer);
        }
        break;  // A lost device: create one on the new device.
    }
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = "staging";
    descriptor.size = std::max(kSmallestBuffer, std::bit_ceil(size));
    descriptor.usage = wgpu::BufferUsage::MapWrite | wgpu::BufferUsage::CopySrc;
    descriptor.mappedAtCreation = true;
    ++mCreated;
    return mContext.device().CreateBuffer(&descriptor);
}

void StagingBuffers::giveBack(wgpu::Buffer buffer, bool mapped) {
    if (!buffer || mBytes + buffer.GetSize() > mKeptBytes) {
        return;  // Freed once the GPU is done with it.
    }
    mBytes += buffer.GetSize();
    if (mapped) {
        mFree.push_back(std::move(buffer));
        return;
    }
    auto remapping = std::make_unique<Remapping>();
    remapping->buffer = std::move(buffer);
    remapping->future = remapping->buffer.MapAsync(
        wgpu::MapMode::Write, 0, remapping->buffer.GetSize(), wgpu::CallbackMode::WaitAnyOnly,
        [mapped = remapping->mapped](wgpu::MapAsyncStatus status, wgpu::StringView) {
            *mapped = status == wgpu::MapAsyncStatus::Success;
        });
    mRemapping.push_back(std::move(remapping));
}

}  // namespace encore::gpu
