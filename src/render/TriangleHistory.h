#pragma once

// The per-frame history of GPU-counted triangles (Renderer::setTriangleCounting): each frame
// copies the culling pass's one-word count into the next slot of a history on the GPU, so that
// no frame waits for a readback; take() reads the history back afterwards. The history grows
// in chunks of kFramesPerChunk words and never moves what it holds, so a frame's copy is always
// a single 4-byte copyBufferToBuffer; the first chunk exists from the start, so the first 1024
// frames allocate nothing.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"

namespace encore::render {

class TriangleHistory {
  public:
    static constexpr std::uint32_t kFramesPerChunk = 1024;  // 4 KiB per chunk.

    explicit TriangleHistory(wgpu::Device device);

    // Records the copy of the u32 at `offset` of `source` (CopySrc usage) into the next slot.
    void record(const wgpu::CommandEncoder& commands,
                const wgpu::Buffer& source,
                std::uint64_t offset);
    // Waits for the GPU and returns one value per frame recorded since the last take, which
    // starts a new history.
    Result<std::vector<std::uint64_t>> take(gpu::Context& context);
    std::uint64_t frames() const { return mFrames; }

  private:
    void addChunk();

    wgpu::Device mDevice;
    std::vector<wgpu::Buffer> mChunks;
    std::uint64_t mFrames = 0;
};

}  // namespace encore::render
