#pragma once

// Staging buffers for uploads (MapWrite | CopySrc), kept and mapped again once the GPU has copied
// out of them. Creating a large buffer mapped at creation costs the driver an allocation and the
// kernel fresh pages each time: on the H100, staging a model's images in new buffers took the
// device's thread about 8 ms per model of `encore batch`. Reused buffers are mapped already
// when they are handed out.
//
// Only the thread that owns the device calls this object. The context must outlive it.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "encore/gpu/Context.h"

namespace encore::gpu {

class StagingBuffers {
  public:
    // Keeps at most `keptBytes` of buffers (given back beyond it, they are freed).
    explicit StagingBuffers(Context& context, std::uint64_t keptBytes = std::uint64_t{512} << 20);
    // Waits for the mappings still pending (their callbacks refer to this object).
    ~StagingBuffers();
    StagingBuffers(const StagingBuffers&) = delete;
    StagingBuffers& operator=(const StagingBuffers&) = delete;

    // A buffer of at least `size` bytes, mapped for writing over its whole size: a kept one
    // whose mapping has finished, else a kept one once its mapping finishes (waiting for the
    // GPU to pass the copy out of it), else a new one (its size rounded up to a power of two of
    // at least 1 MiB, so that it serves later sizes too).
    wgpu::Buffer acquire(std::uint64_t size);
    // Takes back a buffer from acquire(): mapped still (nothing was copied from it), or unmapped
    // with the copies out of it submitted, in which case it is mapped again for a later acquire.
    void giveBack(wgpu::Buffer buffer, bool mapped);

    std::size_t created() const { return mCreated; }

  private:
    struct Remapping {
        wgpu::Buffer buffer;
        wgpu::Future future;
        // Set by the callback, which runs inside Context::wait, or when the instance drops the
        // lost device's pending mappings: shared with it, since after a device loss this object
        // may be gone by then (its destructor waits for no mapping of a lost device).
        std::shared_ptr<bool> mapped = std::make_shared<bool>(false);
    };
    // Moves the buffers whose mapping finished to the free list.
    void collect();
    // The smallest free buffer of at least `size` bytes, taken off the list; null when none.
    wgpu::Buffer takeFree(std::uint64_t size);

    Context& mContext;
    // The device the buffers belong to: after a device loss the context holds a new one, and
    // the old one's mappings are neither waited for nor reused.
    wgpu::Device mDevice;
    std::uint64_t mKeptBytes;
    std::uint64_t mBytes = 0;         // Of every buffer kept, mapped or mapping.
    std::vector<wgpu::Buffer> mFree;  // Mapped.
    std::deque<std::unique_ptr<Remapping>> mRemapping;
    std::size_t mCreated = 0;
};

}  // namespace encore::gpu
