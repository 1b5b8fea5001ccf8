#pragma once

// Reads RGBA8 textures back without stalling the CPU on the GPU: each read copies the texture
// into one of a fixed ring of staging buffers and starts mapping it (mapAsync); the caller
// submits more work and collects finished reads later, oldest first. For pipelines that render
// many frames and read every one back (encore batch); gpu::readTexture is the blocking,
// one-off form.
//
// A finished read can stay mapped (takeOldestMapped): other threads then read its rows straight
// from the staging buffer, and the ring unmaps it once they let go. The thread that owns the
// device does no copying of its own.

#include <webgpu/webgpu_cpp.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"
#include "gpu/StageTimestamps.h"

namespace encore::gpu {

struct FinishedReadback {
    std::uint64_t ticket = 0;       // What enqueue() returned for this read.
    image::ImageRgba8 image;        // RGBA, rows top to bottom, bytes as stored.
    double waitMilliseconds = 0.0;  // Blocked until the GPU had finished the copy.
    double copyMilliseconds = 0.0;  // Unpacking the mapped rows.
};

// A finished read whose rows are still in the ring's mapped buffer. Any thread may read them
// while a copy of this object lives; when the last copy goes, the ring may unmap the buffer and
// reuse it (on its own thread, at a later enqueue()).
struct MappedReadback {
    std::uint64_t ticket = 0;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t bytesPerRow = 0;       // Between the starts of rows (gpu::paddedRowBytes).
    std::uint32_t bytesPerTexel = 4;     // 4: RGBA8; 8: RGBA16Float (half floats).
    const std::uint8_t* rows = nullptr;  // RGBA, rows top to bottom, bytes as stored.
    std::uint64_t size = 0;              // Bytes mapped from `rows` on.
    double waitMilliseconds = 0.0;       // Blocked until the GPU had finished the copy.
    std::shared_ptr<const void> hold;    // Keeps the buffer mapped.
};

class TextureReadbackRing {
  public:
    // `slots` staging buffers (at least 1), created on first use at the size a read needs. The
    // context must outlive the ring.
    TextureReadbackRing(Context& context, std::size_t slots);
    // Waits for reads still in flight (their callbacks refer to the ring) and for the mapped
    // reads still held elsewhere.
    ~TextureReadbackRing();
    TextureReadbackRing(const TextureReadbackRing&) = delete;
    TextureReadbackRing& operator=(const TextureReadbackRing&) = delete;

    // Every slot holds a read not yet taken: take one before enqueueing another.
    bool full() const { return mInFlight.size() == mSlots.size(); }
    // Gives every slot a buffer of at least `bytes` now, so that reads of up to that size create
    // none later, however many are in flight at once (a batch's steady state creates no GPU
    // object). Call with no read in flight.
    void reserve(std::uint64_t bytes);
    bool empty() const { return mInFlight.empty(); }
    // Whether the oldest read has finished on the GPU (takeOldest will not block).
    bool oldestReady() const;

    // Submits a copy of mip level 0 of `texture` (RGBA8Unorm, RGBA8UnormSrgb or RGBA16Float:
    // the HDR and pass images of encore batch; CopySrc) into
    // a free slot and starts mapping it; when every slot not in flight is still held
    // (MappedReadback), waits for one to be let go. Fails when the ring is full or the
    // texture's rows do not fit the device's maxBufferSize. With `timestamps`, the copy is timed
    // as `stage`.
    Result<std::uint64_t> enqueue(const wgpu::Texture& texture,
                                  StageTimestamps* timestamps = nullptr,
                                  std::uint32_t stage = 0);
    // The same for a read that GPU commands fill: `record` records into the encoder what writes
    // `size` bytes of the slot's buffer (from 0; a multiple of 4), as a copy from a buffer a
    // compute pass wrote (batch/PngRowsPass). The mapped read's `rows` are those bytes (its
    // width, height and bytesPerRow 0).
    Result<std::uint64_t> enqueueCommands(
        std::uint64_t size,
        const std::function<void(const wgpu::CommandEncoder&, const wgpu::Buffer&)>& record,
        StageTimestamps* timestamps = nullptr,
        std::uint32_t stage = 0);
    // Waits for the oldest read and returns its image; its slot is free again. Fails with a
    // DeviceError when mapping failed (a lost device); RGBA8 reads only.
    Result<FinishedReadback> takeOldest();
    // The same, leaving the rows in the mapped buffer for the holders of the result to read.
    Result<MappedReadback> takeOldestMapped();

  private:
    struct Slot;
    // What the holders of a mapped read share with the ring, which may be gone before them.
    struct Releases {
        std::mutex mutex;
        std::condition_variable released;
    };

    // A slot neither in flight nor held, unmapped; waits for a holder to let go if need be.
    // Null when every slot is in flight.
    Slot* freeSlot();
    // A free slot whose buffer holds at least `size` bytes, or why there is none (`what` needs
    // the bytes, for the message).
    Result<Slot*> slotFor(std::uint64_t size, const std::string& what);
    // Submits `encoder`'s commands, which fill the slot, and starts mapping its first `size`
    // bytes.
    std::uint64_t submitAndMap(Slot& slot, const wgpu::CommandEncoder& encoder, std::uint64_t size);

    Context* mContext;
    std::vector<std::shared_ptr<Slot>> mSlots;
    std::deque<Slot*> mInFlight;  // Oldest first.
    std::shared_ptr<Releases> mReleases = std::make_shared<Releases>();
    std::uint64_t mNextTicket = 0;
};

}  // namespace encore::gpu
