#include "render/StagedGeometry.h"

#include <algorithm>
#include <cstring>

#include "core/Bytes.h"
#include "gpu/Upload.h"

namespace encore::render {

std::unique_ptr<StagedGeometry> StagedGeometry::stage(const scene::SceneData& scene,
                                                      std::uint64_t maxBufferBytes,
                                                      const Run& run,
                                                      std::shared_ptr<gpu::StagingBuffers> buffers,
                                                      std::uint64_t pieceBytes) {
    std::unique_ptr<StagedGeometry> staged(new StagedGeometry());
    pieceBytes = std::max<std::uint64_t>(pieceBytes, 1);
    staged->mBuffers = std::move(buffers);
    staged->mLayout = sharedGeometryLayout(scene, maxBufferBytes);
    staged->mStaged.resize(staged->mLayout.buffers.size());
    for (std::size_t index = 0; index < staged->mLayout.buffers.size(); ++index) {
        const SharedGeometryLayout::Buffer& layout = staged->mLayout.buffers[index];
        Staged& target = staged->mStaged[index];
        const std::uint64_t size = gpu::bufferSizeFor(layout.size);
        target.buffer = staged->mBuffers->acquire(size);
        auto* mapped = static_cast<std::uint8_t*>(target.buffer.GetMappedRange(0, size));
        if (!mapped) {
            continue;  // Out of memory: GeometryBuffers uploads this one itself.
        }
        staged->mBytes += size;
        // Parts in order, gathered into pieces of pieceBytes.
        auto piece = std::make_shared<Piece>();
        std::uint64_t filled = 0;  // Bytes of `piece`.
        const auto add = [&](std::uint64_t offset, const std::uint8_t* source,
                             std::uint64_t length) {
            while (length > 0) {
                const std::uint64_t part = std::min(length, pieceBytes - filled);
                piece->parts.push_back({mapped + offset, source, part});
                offset += part;
                source = source ? source + part : nullptr;
                length -= part;
                filled += part;
                if (filled == pieceBytes) {
                    target.pieces.push_back(std::exchange(piece, std::make_shared<Piece>()));
                    filled = 0;
                }
            }
        };
        std::uint64_t end = 0;
        for (const SharedGeometryLayout::View& view : layout.views) {
            add(end, nullptr, view.offset - end);
            const scene::BufferView& source = scene.bufferViews[view.id.index()];
            add(view.offset, scene.buffers[source.buffer.index()].bytes.data() + source.byteOffset,
                view.length);
            end = view.offset + view.length;
        }
        add(end, nullptr, size - end);
        if (!piece->parts.empty()) {
            target.pieces.push_back(std::move(piece));
        }
        for (const auto& each : target.pieces) {
            run([each, finished = staged->mFinished] {
                each->copy.run(*finished, [&] { copyParts(*each); });
            });
        }
    }
    return staged;
}

StagedGeometry::~StagedGeometry() {
    // Pieces not started never run; running ones write into the buffers and read the scene:
    // wait for them.
    for (const Staged& staged : mStaged) {
        for (const auto& piece : staged.pieces) {
            piece->copy.cancel(*mFinished);
        }
    }
    for (Staged& staged : mStaged) {
        mBuffers->giveBack(std::move(staged.buffer), !staged.unmapped);
    }
}

void StagedGeometry::copyParts(const Piece& piece) {
    for (const Piece::Part& part : piece.parts) {
        if (part.source) {
            copyBytes(part.destination, part.source, part.length);
        } else {
            std::memset(part.destination, 0, part.length);
        }
    }
}

wgpu::Buffer StagedGeometry::copySource(std::size_t index) {
    if (index >= mStaged.size() || (mStaged[index].pieces.empty() && !mStaged[index].unmapped)) {
        return nullptr;
    }
    Staged& staged = mStaged[index];
    if (!staged.unmapped) {
        for (const auto& piece : staged.pieces) {  // Nothing for those a worker has.
            piece->copy.run(*mFinished, [&] { copyParts(*piece); });
        }
        for (const auto& piece : staged.pieces) {
            piece->copy.wait(*mFinished);
        }
        staged.buffer.Unmap();
        staged.unmapped = true;
    }
    return staged.buffer;
}

}  // namespace encore::render
