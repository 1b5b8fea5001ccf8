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
                                        kFramesPerChunk * 4, "drawn triangles per frame"));
}

void TriangleHistory::record(const wgpu::CommandEncoder& commands,
                             const wgpu::Buffer& source,
                             std::uint64_t offset) {
    const std::uint64_t chunk = mFrames / kFramesPerChunk;
    if (chunk == mChunks.size()) {
        addChunk();
    }
    commands.CopyBufferToBuffer(source, offset, mChunks[chunk], (mFrames % kFramesPerChunk) * 4, 4);
    ++mFrames;
}

Result<std::vector<std::uint64_t>> TriangleHistory::take(gpu::Context& context) {
    std::vector<std::uint64_t> values;
    values.reserve(mFrames);
    for (std::size_t chunk = 0; chunk < mChunks.size(); ++chunk) {
        const std::uint64_t count =
            std::min<std::uint64_t>(mFrames - chunk * kFramesPerChunk, kFramesPerChunk);
        if (count == 0) {
            break;
        }
        auto bytes = gpu::readBuffer(context, mChunks[chunk], 0, count * 4);
        if (!bytes) {
            return bytes.error().withContext("Reading the drawn-triangle counts back");
        }
        for (std::uint64_t frame = 0; frame < count; ++frame) {
            std::uint32_t value;
            std::memcpy(&value, bytes->data() + frame * 4, 4);
            values.push_back(value);
        }
    }
    mChunks.resize(1);  // The first chunk serves the next history.
    mFrames = 0;
    return values;
}

}  // namespace encore::render
