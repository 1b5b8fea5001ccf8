#include "batch/PngRowsPass.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "batch/PassImages.h"
#include "batch/ViewStrips.h"
#include "gpu/BindingResource.h"
#include "gpu/Upload.h"
#include "shaders/ShaderLibrary.h"

namespace encore::batch {
namespace {

constexpr std::uint32_t kWorkgroupSize = 64;   // png_rows.wgsl's.
constexpr std::uint32_t kMaxGroupsX = 65535;   // WebGPU's default maxComputeWorkgroupsPerDimension.
constexpr std::uint64_t kUniformStride = 256;  // minUniformBufferOffsetAlignment, at most.

// png_rows.wgsl's Rows.
struct RowsUniform {
    std::uint32_t viewSize[2];
    std::uint32_t source;
    std::uint32_t rowFilter;
    std::uint32_t bytesPerPixel;
    std::uint32_t viewWords;
    std::uint32_t firstWord;
    std::uint32_t counted;
    std::uint32_t groupsX;
    float depthFactor;
    std::uint32_t padding[2];
};
static_assert(sizeof(RowsUniform) == 48);

std::uint64_t alignedToWords(std::uint64_t bytes) {
    return (bytes + 3) & ~std::uint64_t(3);
}

wgpu::Buffer storageBuffer(const wgpu::Device& device,
                           std::uint64_t size,
                           wgpu::BufferUsage extra,
                           const char* label) {
    wgpu::BufferDescriptor descriptor{};
    descriptor.label = label;
    descriptor.size = std::max<std::uint64_t>(size, 4);
    descriptor.usage = wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopySrc | extra;
    return device.CreateBuffer(&descriptor);
}

}  // namespace

std::span<const std::uint8_t> PngRowsLayout::rows(const std::uint8_t* readback,
                                                  std::size_t image,
                                                  std::uint32_t view) const {
    const Image& described = images[image];
    return {readback + described.offset + std::uint64_t(view) * described.viewStride,
            described.rowsSize};
}

std::uint32_t PngRowsLayout::coveredPixels(const std::uint8_t* readback, std::uint32_t view) const {
    std::uint32_t count = 0;
    if (coverageOffset) {
        std::memcpy(&count, readback + *coverageOffset + std::uint64_t(view) * 4, 4);
    }
    return count;
}

PngRowsSource pngRowsSourceOf(ViewImage kind) {
    switch (kind) {
        case ViewImage::Normal:
        case ViewImage::Material:
            return PngRowsSource::LinearBytes;
        case ViewImage::Depth:
            return PngRowsSource::Depth;
        case ViewImage::Segmentation:
            return PngRowsSource::Ids;
        case ViewImage::Color:
        case ViewImage::Albedo:
        case ViewImage::Hdr:
        case ViewImage::Coordinates:
            break;
    }
    return PngRowsSource::Bytes;
}

PngRowsLayout pngRowsLayout(std::uint32_t width,
                            std::uint32_t height,
                            std::uint32_t views,
                            std::span<const PngRowsRequest> requests,
                            image::PngCompression compression) {
    PngRowsLayout layout;
    layout.width = width;
    layout.height = height;
    layout.views = views;
    std::uint64_t offset = 0;
    bool color = false;
    for (const PngRowsRequest& request : requests) {
        PngRowsLayout::Image image;
        image.kind = request.kind;
        image.source = request.source;
        const bool sixteenBits =
            request.source == PngRowsSource::Depth || request.source == PngRowsSource::Ids;
        image.bitDepth = sixteenBits ? 16 : 8;
        image.color = sixteenBits ? image::PngColor::Gray : image::PngColor::Rgba;
        image.compression = pngCompressionOf(request.kind, compression);
        image.rowsSize = image::filteredPngSize(width, height, image.bitDepth, image.color);
        image.viewStride = alignedToWords(image.rowsSize);
        image.offset = offset;
        offset += image.viewStride * views;
        color = color || request.kind == ViewImage::Color;
        layout.images.push_back(image);
    }
    if (color) {
        layout.coverageOffset = offset;
        offset += std::uint64_t(views) * 4;
    }
    layout.size = offset;
    return layout;
}

Result<PngRowsPass> PngRowsPass::create(const wgpu::Device& device) {
    PngRowsPass pass;
    pass.mDevice = device;
    shaders::ShaderLibrary shaders(device);
    ENCORE_TRY_ASSIGN(auto module, shaders.module("png_rows.wgsl"));
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.label = "PNG rows";
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = "writeRows";
    pass.mPipeline = device.CreateComputePipeline(&descriptor);
    pass.mLayout = pass.mPipeline.GetBindGroupLayout(0);
    std::array<std::uint32_t, 256> table{};
    const std::array<std::uint8_t, 256>& linear = srgbDecodedBytes();
    std::copy(linear.begin(), linear.end(), table.begin());
    pass.mLinearOfSrgb = gpu::createBufferFrom<std::uint32_t>(
        device, wgpu::BufferUsage::Uniform, table, "PNG rows: sRGB-decoded bytes");
    return pass;
}

void PngRowsPass::record(const wgpu::Queue& queue,
                         const wgpu::CommandEncoder& encoder,
                         const wgpu::TextureView& source,
                         const PngRowsLayout& layout,
                         float depthFactor,
                         const wgpu::Buffer& destination) {
    const std::uint64_t rowsSize = layout.coverageOffset.value_or(layout.size);
    if (!mRows || mRows.GetSize() < rowsSize) {
        mRows = storageBuffer(mDevice, rowsSize, wgpu::BufferUsage::None, "PNG rows");
    }
    const std::uint64_t countsSize = std::uint64_t(layout.views) * 4;
    if (!mCovered || mCovered.GetSize() < countsSize) {
        mCovered = storageBuffer(mDevice, countsSize, wgpu::BufferUsage::CopyDst,
                                 "PNG rows: covered pixels");
    }
    if (mUniformSlots < layout.images.size()) {
        wgpu::BufferDescriptor descriptor{};
        descriptor.label = "PNG rows: uniforms";
        descriptor.size = kUniformStride * layout.images.size();
        descriptor.usage = wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst;
        mUniforms = mDevice.CreateBuffer(&descriptor);
        mUniformSlots = layout.images.size();
    }

    std::vector<std::uint8_t> uniforms(kUniformStride * layout.images.size(), 0);
    std::vector<std::array<std::uint32_t, 3>> grids;
    for (std::size_t i = 0; i < layout.images.size(); ++i) {
        const PngRowsLayout::Image& image = layout.images[i];
        const auto viewWords = std::uint32_t(image.viewStride / 4);
        const std::uint32_t groups = (viewWords + kWorkgroupSize - 1) / kWorkgroupSize;
        const std::uint32_t groupsX = std::min(groups, kMaxGroupsX);
        RowsUniform uniform{};
        uniform.viewSize[0] = layout.width;
        uniform.viewSize[1] = layout.height;
        uniform.source = std::uint32_t(image.source);
        uniform.rowFilter =
            image::pngRowFilter(image.bitDepth, image.compression) == image::PngRowFilter::Paeth
                ? 1
                : 0;
        uniform.bytesPerPixel = std::uint32_t(image::pngBytesPerPixel(image.bitDepth, image.color));
        uniform.viewWords = viewWords;
        uniform.firstWord = std::uint32_t(image.offset / 4);
        uniform.counted = image.kind == ViewImage::Color ? 1 : 0;
        uniform.groupsX = groupsX;
        uniform.depthFactor = depthFactor;
        std::memcpy(&uniforms[i * kUniformStride], &uniform, sizeof(uniform));
        grids.push_back({groupsX, layout.views, (groups + groupsX - 1) / groupsX});
    }
    queue.WriteBuffer(mUniforms, 0, uniforms.data(), uniforms.size());

    if (layout.coverageOffset) {
        encoder.ClearBuffer(mCovered, 0, countsSize);
    }
    wgpu::ComputePassDescriptor passDescriptor{};
    passDescriptor.label = "PNG rows";
    wgpu::ComputePassEncoder pass = encoder.BeginComputePass(&passDescriptor);
    pass.SetPipeline(mPipeline);
    for (std::size_t i = 0; i < layout.images.size(); ++i) {
        const wgpu::BindGroup group =
            gpu::makeBindGroup(mDevice, mLayout,
                               {{0, source},
                                {1, mRows},
                                {2, mUniforms, i * kUniformStride, sizeof(RowsUniform)},
                                {3, mLinearOfSrgb},
                                {4, mCovered}},
                               "PNG rows");
        pass.SetBindGroup(0, group);
        pass.DispatchWorkgroups(grids[i][0], grids[i][1], grids[i][2]);
    }
    pass.End();
    encoder.CopyBufferToBuffer(mRows, 0, destination, 0, rowsSize);
    if (layout.coverageOffset) {
        encoder.CopyBufferToBuffer(mCovered, 0, destination, *layout.coverageOffset, countsSize);
    }
}

bool filtersPngRowsOnGpu(PngFiltering filtering, wgpu::AdapterType adapter) {
    switch (filtering) {
        case PngFiltering::Gpu:
            return true;
        case PngFiltering::Cpu:
            return false;
        case PngFiltering::Auto:
            break;
    }
    return adapter != wgpu::AdapterType::CPU;
}

}  // namespace encore::batch
