#include "render/StagedImages.h"

#include <cstring>

#include "core/Bytes.h"
#include "gpu/Readback.h"

namespace encore::render {

std::unique_ptr<StagedImages> StagedImages::stage(const wgpu::Device& device,
                                                  const scene::SceneData& scene,
                                                  std::uint32_t maxDimension,
                                                  const Run& run,
                                                  std::shared_ptr<gpu::StagingBuffers> buffers) {
    std::unique_ptr<StagedImages> staged(new StagedImages());
    staged->mBuffers = std::move(buffers);
    staged->mImages.resize(scene.images.size());
    for (std::size_t index = 0; index < scene.images.size(); ++index) {
        const scene::Image& source = scene.images[index];
        const std::uint64_t tight = std::uint64_t(source.width) * source.height * 4;
        if (source.rgba8.empty() || source.width == 0 || source.height == 0 ||
            source.rgba8.size() != tight || source.width > maxDimension ||
            source.height > maxDimension) {
            continue;  // MaterialResources reports or downscales these itself.
        }
        auto image = std::make_shared<Image>();
        image->source = &source;
        // A buffer-to-texture copy's rows are the same 256-byte multiple as a read-back's.
        image->bytesPerRow = gpu::paddedRowBytes(source.width * 4);
        const std::uint64_t size = std::uint64_t(image->bytesPerRow) * source.height;
        if (staged->mBuffers) {
            image->buffer = staged->mBuffers->acquire(size);
        } else {
            wgpu::BufferDescriptor descriptor{};
            descriptor.label = "staged image";
            descriptor.size = size;
            descriptor.usage = wgpu::BufferUsage::CopySrc;
            descriptor.mappedAtCreation = true;
            image->buffer = device.CreateBuffer(&descriptor);
        }
        image->mapped = static_cast<std::uint8_t*>(image->buffer.GetMappedRange(0, size));
        if (!image->mapped) {
            continue;  // Out of memory: WriteTexture will try (and report) instead.
        }
        staged->mBytes += size;
        run([image, finished = staged->mFinished] {
            image->copy.run(*finished, [&] { copyRows(*image); });
        });
        staged->mImages[index] = std::move(image);
    }
    return staged;
}

StagedImages::~StagedImages() {
    // Copies not started never run; running ones write into the buffers and read the scene:
    // wait for them.
    for (const auto& image : mImages) {
        if (image) {
            image->copy.cancel(*mFinished);
        }
    }
    if (mBuffers) {
        for (const auto& image : mImages) {
            if (image) {
                mBuffers->giveBack(std::move(image->buffer), !image->unmapped);
            }
        }
    }
}

void StagedImages::copyRows(const Image& image) {
    const scene::Image& source = *image.source;
    const std::uint32_t rowBytes = source.width * 4;
    if (rowBytes == image.bytesPerRow) {
        copyBytes(image.mapped, source.rgba8.data(), source.rgba8.size());
    } else {
        for (std::uint32_t y = 0; y < source.height; ++y) {
            std::memcpy(image.mapped + std::size_t(y) * image.bytesPerRow,
                        source.rgba8.data() + std::size_t(y) * rowBytes, rowBytes);
        }
    }
}

std::optional<wgpu::TexelCopyBufferInfo> StagedImages::copySource(scene::ImageId id) {
    if (!id.valid() || id.index() >= mImages.size() || !mImages[id.index()]) {
        return std::nullopt;
    }
    Image& image = *mImages[id.index()];
    if (!image.unmapped) {
        image.copy.run(*mFinished, [&] { copyRows(image); });  // Nothing when a worker has it.
        image.copy.wait(*mFinished);
        image.buffer.Unmap();
        image.unmapped = true;
    }
    wgpu::TexelCopyBufferInfo source{};
    source.buffer = image.buffer;
    source.layout.bytesPerRow = image.bytesPerRow;
    source.layout.rowsPerImage = image.source->height;
    return source;
}

}  // namespace encore::render
