#pragma once

// A scene's images copied into staging buffers by other threads, ahead of Renderer::prepare.
//
// Without it, MaterialResources hands each image to Queue::WriteTexture, which copies the pixels
// into Dawn's staging memory on the thread that owns the device: for a model with three
// 2048x2048 textures that is 48 MiB copied while nothing else is recorded. stage() takes one
// mapped buffer per image (rows padded to a texture copy's bytesPerRow) on the device's thread,
// from gpu::StagingBuffers when given (reused buffers: creating large ones costs as much as the
// copy saved), and hands the copying of the pixels to `run` (a thread pool); prepare then only
// waits for the copies it needs, unmaps, and records buffer-to-texture copies. The textures hold
// the same bytes either way.
//
// Only the thread that owns the device calls stage(), copySource() and the destructor; the
// destructor waits for copies still running. The scene must outlive this object.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/ClaimedTask.h"
#include "encore/scene/SceneData.h"
#include "gpu/StagingBuffers.h"

namespace encore::render {

class StagedImages {
  public:
    using Run = std::function<void(std::function<void()>)>;

    // Stages every image of `scene` that has pixels and fits within `maxDimension` (others are
    // left to WriteTexture, which MaterialResources downscales first); `run` is called on this
    // thread once per image with the task that copies it. The buffers come from `buffers` and
    // go back to it when given (kept alive for that: a batch makes a new one after a device
    // loss), else they are created mapped.
    static std::unique_ptr<StagedImages> stage(const wgpu::Device& device,
                                               const scene::SceneData& scene,
                                               std::uint32_t maxDimension,
                                               const Run& run,
                                               std::shared_ptr<gpu::StagingBuffers> buffers = {});
    ~StagedImages();
    StagedImages(const StagedImages&) = delete;
    StagedImages& operator=(const StagedImages&) = delete;

    // The copy source of image `id` (width x height RGBA8 rows, bytesPerRow a multiple of 256),
    // once its rows are in the buffer and it is unmapped; nullopt when the image was not
    // staged. When no thread has started the copy yet, this thread makes it.
    std::optional<wgpu::TexelCopyBufferInfo> copySource(scene::ImageId id);

    // Bytes staged, for statistics.
    std::uint64_t bytes() const { return mBytes; }

  private:
    struct Image {
        wgpu::Buffer buffer;
        std::uint8_t* mapped = nullptr;
        const scene::Image* source = nullptr;
        std::uint32_t bytesPerRow = 0;
        ClaimedTask copy;       // Of the rows into the mapping.
        bool unmapped = false;  // The device thread's only.
    };
    StagedImages() = default;
    static void copyRows(const Image& image);

    std::vector<std::shared_ptr<Image>> mImages;  // Indexed by ImageId; null: not staged.
    // Shared with the copy tasks, which may run after this object is gone.
    std::shared_ptr<ClaimedTask::Finished> mFinished = std::make_shared<ClaimedTask::Finished>();
    std::shared_ptr<gpu::StagingBuffers> mBuffers;
    std::uint64_t mBytes = 0;
};

}  // namespace encore::render
