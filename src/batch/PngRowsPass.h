#pragma once

// encore batch's PNG rows filtered on the GPU (png_rows.wgsl): for each view of a wide target
// and each image asked of it, the bytes that image/PngWriter's filterPngRows would make from the
// read-back, written side by side into a buffer that the read-back ring maps. The pool then only
// compresses them (image::pngOfFilteredRows): no cropping, no conversion of half floats, no
// filtering on the CPU, where a batch with every pass spends most of its time
// (docs/batch.md#where-png-rows-are-filtered). The PNG files are byte for byte those of the CPU
// path, depth within one step (the GPU rounds its float division its own way).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "encore/batch/Batch.h"
#include "encore/batch/ViewImages.h"
#include "encore/core/Result.h"
#include "encore/image/ImageCodec.h"
#include "image/PngWriter.h"

namespace encore::batch {

// What a texture holds and which samples an image takes from it (png_rows.wgsl says how).
enum class PngRowsSource : std::uint32_t {
    Bytes = 0,        // RGBA8, read through an rgba8unorm view: the colour image, albedo.
    LinearBytes = 1,  // The same, R, G and B sRGB-decoded (decodeNormalImage): normal, material.
    Depth = 2,        // 16-bit depth from the depth-and-id target (depthStrip's values).
    Ids = 3,          // 16-bit segmentation ids from the same target.
};

// Where an image of `kind` takes its samples from (the colour and albedo as stored, normal and
// material sRGB-decoded, depth and ids from the depth-and-id target), as the CPU path makes them.
PngRowsSource pngRowsSourceOf(ViewImage kind);

struct PngRowsRequest {
    ViewImage kind = ViewImage::Color;
    PngRowsSource source = PngRowsSource::Bytes;
};

// Where the filtered rows of one read lie in its read-back: images one after the other, each
// view's rows inside an image 4-byte aligned; then, when the colour image is among them, a
// 32-bit count per view of the pixels whose alpha is not 0 (ModelMetadata's coveredPixels).
struct PngRowsLayout {
    struct Image {
        ViewImage kind = ViewImage::Color;
        PngRowsSource source = PngRowsSource::Bytes;
        std::uint8_t bitDepth = 8;
        image::PngColor color = image::PngColor::Rgba;
        image::PngCompression compression = image::PngCompression::Small;
        std::uint64_t offset = 0;      // Of view 0's rows.
        std::uint64_t viewStride = 0;  // From one view's rows to the next's.
        std::uint64_t rowsSize = 0;    // image::filteredPngSize.
    };
    std::uint32_t width = 0;  // Of one view.
    std::uint32_t height = 0;
    std::uint32_t views = 0;
    std::vector<Image> images;
    std::optional<std::uint64_t> coverageOffset;
    std::uint64_t size = 0;  // Of the whole read-back.

    std::span<const std::uint8_t> rows(const std::uint8_t* readback,
                                       std::size_t image,
                                       std::uint32_t view) const;
    std::uint32_t coveredPixels(const std::uint8_t* readback, std::uint32_t view) const;
};

// The layout of `views` views of width x height with `requests`' images, each compressed as
// pngCompressionOf(kind, compression) says.
PngRowsLayout pngRowsLayout(std::uint32_t width,
                            std::uint32_t height,
                            std::uint32_t views,
                            std::span<const PngRowsRequest> requests,
                            image::PngCompression compression);

class PngRowsPass {
  public:
    static Result<PngRowsPass> create(const wgpu::Device& device);

    // Records into `encoder` the dispatches that write `layout`'s rows from `source` (the
    // views side by side, strip i at x = i * width) and their copy into `destination` (at 0,
    // layout.size bytes). `depthFactor`: depth steps per unit of the depth-and-id target's
    // depth (unitsPerModelUnit / depthScale). Writes its uniforms through `queue` (before the
    // caller submits).
    void record(const wgpu::Queue& queue,
                const wgpu::CommandEncoder& encoder,
                const wgpu::TextureView& source,
                const PngRowsLayout& layout,
                float depthFactor,
                const wgpu::Buffer& destination);

  private:
    PngRowsPass() = default;

    wgpu::Device mDevice;
    wgpu::ComputePipeline mPipeline;
    wgpu::BindGroupLayout mLayout;
    wgpu::Buffer mLinearOfSrgb;  // The 256 bytes of decodeNormalImage's table, one u32 each.
    wgpu::Buffer mUniforms;      // One slot per image of a read.
    std::size_t mUniformSlots = 0;
    wgpu::Buffer mRows;     // Storage: what the dispatches write, copied into `destination`.
    wgpu::Buffer mCovered;  // Storage: the colour image's counts.
};

// Whether a batch filters its PNG rows on the GPU: asked, or left to Auto on an adapter that is
// not a CPU (on lavapipe the "GPU" is the CPU's cores, which the pool needs).
bool filtersPngRowsOnGpu(PngFiltering filtering, wgpu::AdapterType adapter);

}  // namespace encore::batch
