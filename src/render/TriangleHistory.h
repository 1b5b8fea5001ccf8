#pragma once

// The per-frame history of GPU-counted triangles (Renderer::setTriangleCounting): each frame
// copies the strategy's counts (GpuTriangleCounts: triangles to the hardware rasteriser and,
// for the visibility strategy, in compute) into the next slot of a history on the GPU, so that
// no frame waits for a readback; take() reads the history back afterwards. The history grows
// in chunks of kFramesPerChunk two-word slots and never moves what it holds, so a frame costs
// a copy (and a clear or a second copy where the two counts are not side by side); the first chunk
// exists from the start, so the first 512 frames allocate nothing.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "render/Strategy.h"

namespace encore::render {

class TriangleHistory {
  public:
    static constexpr std::uint32_t kFramesPerChunk = 512;  // 4 KiB per chunk.

    explicit TriangleHistory(wgpu::Device device);

    // Records the copy of the frame's counts into the next slot (a count the strategy has not
    // is written as zero).
    void record(const wgpu::CommandEncoder& commands, const GpuTriangleCounts& counts);
    // Waits for the GPU and returns one entry per frame recorded since the last take, which
    // starts a new history.
    Result<std::vector<DrawnTriangles>> take(gpu::Context& context);
    std::uint64_t frames() const { return mFrames; }

  private:
    void addChunk();

    wgpu::Device mDevice;
    std::vector<wgpu::Buffer> mChunks;
    std::uint64_t mFrames = 0;
};

}  // namespace encore::render
