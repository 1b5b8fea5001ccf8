#pragma once

// Reads RGBA8 textures back without stalling the CPU on the GPU: each read copies the texture
// into one of a fixed ring of staging buffers and starts mapping it (mapAsync); the caller
// submits more work and collects finished reads later, oldest first. For pipelines that render
// many frames and read every one back (encore batch); gpu::readTexture is the blocking,
// one-off form.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"

namespace encore::gpu {

struct FinishedReadback {
    std::uint64_t ticket = 0;       // What enqueue() returned for this read.
    image::ImageRgba8 image;        // RGBA, rows top to bottom, bytes as stored.
    double waitMilliseconds = 0.0;  // Blocked until the GPU had finished the copy.
    double copyMilliseconds = 0.0;  // Unpacking the mapped rows.
};

class TextureReadbackRing {
  public:
    // `slots` staging buffers (at least 1), created on first use at the size a read needs. The
    // context must outlive the ring.
    TextureReadbackRing(Context& context, std::size_t slots);
    // Waits for reads still in flight (their callbacks refer to the ring).
    ~TextureReadbackRing();
    TextureReadbackRing(const TextureReadbackRing&) = delete;
    TextureReadbackRing& operator=(const TextureReadbackRing&) = delete;

    // Every slot holds a read not yet taken: take one before enqueueing another.
    bool full() const { return mInFlight.size() == mSlots.size(); }
    bool empty() const { return mInFlight.empty(); }
    // Whether the oldest read has finished on the GPU (takeOldest will not block).
    bool oldestReady() const;

    // Submits a copy of mip level 0 of `texture` (RGBA8Unorm or RGBA8UnormSrgb, CopySrc) into
    // a free slot and starts mapping it. Fails when the ring is full or the texture's rows do
    // not fit the device's maxBufferSize.
    Result<std::uint64_t> enqueue(const wgpu::Texture& texture);
    // Waits for the oldest read and returns its image; its slot is free again. Fails with a
    // DeviceError when mapping failed (a lost device).
    Result<FinishedReadback> takeOldest();

  private:
    struct Slot;

    Context* mContext;
    std::vector<std::unique_ptr<Slot>> mSlots;
    std::deque<Slot*> mInFlight;  // Oldest first.
    std::uint64_t mNextTicket = 0;
};

}  // namespace encore::gpu
