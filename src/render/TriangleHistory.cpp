#include "render/TriangleHistory.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "gpu/Readback.h"
#include "gpu/Upload.h"

namespace encore::render {

TriangleHistory::TriangleHistory(wgpu::Device device) : mDevice(std::move(device)) {
    addChunk();
}

void TriangleHistory::addChunk() {
    mChunks.push_back(gpu::createBuffer(mDevice,
                                        wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                                        kFramesPerChunk * 8, "drawn triangles per frame"));
}

void TriangleHistory::record(const wgpu::CommandEncoder& commands,
                             const GpuTriangleCounts& counts) {
    const std::uint64_t chunk = mFrames / kFramesPerChunk;
    if (chunk == mChunks.size()) {
        addChunk();
    }
    // A slot: the compute count, then the hardware count.
    const std::uint64_t slot = (mFrames % kFramesPerChunk) * 8;
    if (counts.computeOffset && *counts.computeOffset + 4 == counts.hardwareOffset) {
        // The visibility strategy's two words: one copy (copies cost a frame more than their
        // bytes: each ends a pass and orders the GPU's work around it).
        commands.CopyBufferToBuffer(counts.buffer, *counts.computeOffset, mChunks[chunk], slot, 8);
    } else {
        if (counts.computeOffset) {
            commands.CopyBufferToBuffer(counts.buffer, *counts.computeOffset, mChunks[chunk], slot,
                                        4);
        } else {
            commands.ClearBuffer(mChunks[chunk], slot, 4);  // A reused chunk holds old counts.
        }
        commands.CopyBufferToBuffer(counts.buffer, counts.hardwareOffset, mChunks[chunk], slot + 4,
                                    4);
    }
    ++mFrames;
}

Result<std::vector<DrawnTriangles>> TriangleHistory::take(gpu::Context& context) {
    std::vector<DrawnTriangles> values;
    values.reserve(mFrames);
    for (std::size_t chunk = 0; chunk < mChunks.size(); ++chunk) {
        const std::uint64_t count =
            std::min<std::uint64_t>(mFrames - chunk * kFramesPerChunk, kFramesPerChunk);
        if (count == 0) {
            break;
        }
        auto bytes = gpu::readBuffer(context, mChunks[chunk], 0, count * 8);
        if (!bytes) {
            return bytes.error().withContext("Reading the drawn-triangle counts back");
        }
        for (std::uint64_t frame = 0; frame < count; ++frame) {
            std::uint32_t words[2];
            std::memcpy(words, bytes->data() + frame * 8, 8);
            values.push_back({words[1], words[0]});
        }
    }
    mChunks.resize(1);  // The first chunk serves the next history.
    mFrames = 0;
    return values;
}

}  // namespace encore::render
