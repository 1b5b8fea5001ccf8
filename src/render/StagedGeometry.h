#pragma once

// A scene's shared geometry (SharedGeometryLayout.h) copied into staging buffers by other
// threads, ahead of Renderer::prepare: the counterpart of StagedImages for vertex and index data.
//
// Without it, GeometryBuffers creates each shared buffer mapped at creation: Dawn then allocates
// a staging buffer of that size, and the kernel hands it fresh pages that the copy faults in and
// zeroes, all on the thread that owns the device (about 6 ms per dense model of `encore batch`,
// on the H100's host and on this project's development VM alike). stage() takes reused, mapped
// buffers from gpu::StagingBuffers on the device's thread and hands the copying, in pieces of a
// few MiB, to `run` (a thread pool); GeometryBuffers then waits for the pieces it needs, unmaps,
// and records buffer-to-buffer copies into buffers created unmapped. The GPU buffers hold the
// same bytes either way (the gaps between views zeroed).
//
// Only the thread that owns the device calls stage(), copySource() and the destructor; the
// destructor waits for pieces still being copied. The scene must outlive this object.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/ClaimedTask.h"
#include "encore/scene/SceneData.h"
#include "gpu/StagingBuffers.h"
#include "render/SharedGeometryLayout.h"

namespace encore::render {

class StagedGeometry {
  public:
    using Run = std::function<void(std::function<void()>)>;
    // Pieces of at most this many bytes are copied by one task.
    static constexpr std::uint64_t kPieceBytes = std::uint64_t{4} << 20;

    // Stages the shared buffers that `maxBufferBytes` (the device's maxBufferSize) lays out;
    // `run` is called on this thread once per piece (of at most `pieceBytes`) with the task
    // that copies it. The buffers come from `buffers` and go back to it.
    static std::unique_ptr<StagedGeometry> stage(const scene::SceneData& scene,
                                                 std::uint64_t maxBufferBytes,
                                                 const Run& run,
                                                 std::shared_ptr<gpu::StagingBuffers> buffers,
                                                 std::uint64_t pieceBytes = kPieceBytes);
    ~StagedGeometry();
    StagedGeometry(const StagedGeometry&) = delete;
    StagedGeometry& operator=(const StagedGeometry&) = delete;

    const SharedGeometryLayout& layout() const { return mLayout; }
    // The staging buffer holding shared buffer `index`'s bytes from offset 0 (its size rounded
    // up to 4, the rest zeros), unmapped, once every piece of it is copied: pieces no thread
    // has started are copied by this one. Null where the staging buffer could not be mapped.
    wgpu::Buffer copySource(std::size_t index);
    // Bytes staged, for statistics.
    std::uint64_t bytes() const { return mBytes; }

  private:
    // One task's copies: bytes of views (source set) and zeros (source null) into a mapping.
    struct Piece {
        struct Part {
            std::uint8_t* destination = nullptr;
            const std::uint8_t* source = nullptr;
            std::uint64_t length = 0;
        };
        std::vector<Part> parts;
        ClaimedTask copy;
    };
    struct Staged {
        wgpu::Buffer buffer;
        std::vector<std::shared_ptr<Piece>> pieces;
        bool unmapped = false;
    };
    StagedGeometry() = default;
    static void copyParts(const Piece& piece);

    SharedGeometryLayout mLayout;
    std::vector<Staged> mStaged;  // Per shared buffer.
    // Shared with the copy tasks, which may run after this object is gone.
    std::shared_ptr<ClaimedTask::Finished> mFinished = std::make_shared<ClaimedTask::Finished>();
    std::shared_ptr<gpu::StagingBuffers> mBuffers;
    std::uint64_t mBytes = 0;
};

}  // namespace encore::render
