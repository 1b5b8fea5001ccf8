#include "gpu/Readback.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include "core/Bytes.h"

namespace encore::gpu {
namespace {

bool isBgra(wgpu::TextureFormat format) {
    return format == wgpu::TextureFormat::BGRA8Unorm ||
           format == wgpu::TextureFormat::BGRA8UnormSrgb;
}

bool isReadableColor(wgpu::TextureFormat format) {
    return isBgra(format) || format == wgpu::TextureFormat::RGBA8Unorm ||
           format == wgpu::TextureFormat::RGBA8UnormSrgb;
}

// Maps a MapRead buffer and copies its contents out.
Result<std::vector<std::uint8_t>> mapAndCopy(Context& context,
                                             const wgpu::Buffer& staging,
                                             std::uint64_t size) {
    bool mapped = false;
    std::string mapMessage;
    context.wait(staging.MapAsync(wgpu::MapMode::Read, 0, size, wgpu::CallbackMode::WaitAnyOnly,
                                  [&](wgpu::MapAsyncStatus status, wgpu::StringView message) {
                                      mapped = status == wgpu::MapAsyncStatus::Success;
                                      mapMessage = std::string(std::string_view(message));
                                  }));
    if (!mapped) {
        return makeError(ErrorCode::DeviceError,
                         "Mapping a readback buffer failed (" + mapMessage + ").");
    }
    const auto* data = static_cast<const std::uint8_t*>(staging.GetConstMappedRange(0, size));
    std::vector<std::uint8_t> bytes(data, data + size);
    staging.Unmap();
    return bytes;
}

// Copies one level and layer of a texture into a staging buffer and returns its rows tightly
// packed (buffer copies need rows aligned to 256 bytes).
Result<std::vector<std::uint8_t>> readTexelRows(Context& context,
                                                const wgpu::Texture& texture,
                                                std::uint32_t level,
                                                std::uint32_t layer,
                                                std::uint32_t bytesPerTexel) {
    const std::uint32_t width = std::max(texture.GetWidth() >> level, 1u);
    const std::uint32_t height = std::max(texture.GetHeight() >> level, 1u);
    const std::uint32_t rowBytes = width * bytesPerTexel;
    const std::uint32_t paddedRowBytes = gpu::paddedRowBytes(rowBytes);
    // Bands of rows, each staging buffer within maxBufferSize: an 8192x8192 rgba16float
    // target is 512 MiB, twice WebGPU's default limit.
    const std::uint64_t maxBufferSize = context.limits().maxBufferSize;
    if (paddedRowBytes > maxBufferSize) {
        return makeError(ErrorCode::LimitExceeded,
                         "Reading back a texture row of " + std::to_string(paddedRowBytes) +
                             " bytes needs a buffer larger than the device's maxBufferSize (" +
                             std::to_string(maxBufferSize) + " bytes).");
    }
    const auto bandRows =
        static_cast<std::uint32_t>(std::min<std::uint64_t>(height, maxBufferSize / paddedRowBytes));
    std::vector<std::uint8_t> rows(std::size_t(rowBytes) * height);
    for (std::uint32_t firstRow = 0; firstRow < height; firstRow += bandRows) {
        const std::uint32_t bandHeight = std::min(bandRows, height - firstRow);
        const std::uint64_t size = std::uint64_t(paddedRowBytes) * bandHeight;
        wgpu::BufferDescriptor stagingDescriptor{};
        stagingDescriptor.label = "texture readback";
        stagingDescriptor.size = size;
        stagingDescriptor.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
        wgpu::Buffer staging = context.device().CreateBuffer(&stagingDescriptor);

        wgpu::TexelCopyTextureInfo source{};
        source.texture = texture;
        source.mipLevel = level;
        source.origin = {0, firstRow, layer};
        wgpu::TexelCopyBufferInfo destination{};
        destination.buffer = staging;
        destination.layout.bytesPerRow = paddedRowBytes;
        destination.layout.rowsPerImage = bandHeight;
        wgpu::Extent3D extent{width, bandHeight, 1};
        wgpu::CommandEncoder encoder = context.device().CreateCommandEncoder();
        encoder.CopyTextureToBuffer(&source, &destination, &extent);
        wgpu::CommandBuffer commands = encoder.Finish();
        context.queue().Submit(1, &commands);

        ENCORE_TRY_ASSIGN(auto bytes, mapAndCopy(context, staging, size));
        unpadRows(bytes.data(), rowBytes, bandHeight, &rows[std::size_t(firstRow) * rowBytes]);
    }
    return rows;
}

}  // namespace

float halfToFloat(std::uint16_t half) {
    // By the bits: the exponent rebased from 15 to 127 and the mantissa widened (read-backs
    // convert millions of texels; ldexp cost most of reading a pass target).
    const std::uint32_t sign = std::uint32_t(half & 0x8000u) << 16;
    const std::uint32_t exponent = (half >> 10) & 0x1fu;
    const std::uint32_t mantissa = half & 0x3ffu;
    if (exponent == 0) {
        const float value = float(mantissa) * 0x1p-24f;  // Zero or subnormal.
        return sign ? -value : value;
    }
    const std::uint32_t bits = exponent == 0x1fu
                                   ? sign | 0x7f800000u | (mantissa << 13)  // Infinity or NaN.
                                   : sign | ((exponent + 112u) << 23) | (mantissa << 13);
    return std::bit_cast<float>(bits);
}

void unpadRows(const std::uint8_t* padded,
               std::uint32_t rowBytes,
               std::uint32_t rows,
               std::uint8_t* packed) {
    const std::size_t stride = paddedRowBytes(rowBytes);
    for (std::uint32_t y = 0; y < rows; ++y) {
        std::memcpy(packed + std::size_t(y) * rowBytes, padded + y * stride, rowBytes);
    }
}

Result<image::ImageRgba8> readTexture(Context& context, const wgpu::Texture& texture) {
    return readTextureLevel(context, texture, 0);
}

Result<image::ImageRgba8> readTextureLevel(Context& context,
                                           const wgpu::Texture& texture,
                                           std::uint32_t level) {
    const auto format = texture.GetFormat();
    if (!isReadableColor(format)) {
        return makeError(ErrorCode::InvalidArgument,
                         "readTexture supports only RGBA8 and BGRA8 textures.");
    }
    if (level >= texture.GetMipLevelCount()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Mip level " + std::to_string(level) +
                             " does not exist (the texture has " +
                             std::to_string(texture.GetMipLevelCount()) + " levels).");
    }
    ENCORE_TRY_ASSIGN(auto rows, readTexelRows(context, texture, level, 0, 4));
    image::ImageRgba8 image;
    image.width = std::max(texture.GetWidth() >> level, 1u);
    image.height = std::max(texture.GetHeight() >> level, 1u);
    image.pixels.assign(rows.begin(), rows.end());
    if (isBgra(format)) {
        for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
            std::swap(image.pixels[i], image.pixels[i + 2]);
        }
    }
    return image;
}

Result<std::vector<float>> readTextureRgba16Float(Context& context,
                                                  const wgpu::Texture& texture,
                                                  std::uint32_t level,
                                                  std::uint32_t layer) {
    if (texture.GetFormat() != wgpu::TextureFormat::RGBA16Float) {
        return makeError(ErrorCode::InvalidArgument,
                         "readTextureRgba16Float needs an RGBA16Float texture.");
    }
    if (level >= texture.GetMipLevelCount() || layer >= texture.GetDepthOrArrayLayers()) {
        return makeError(ErrorCode::InvalidArgument, "Mip level " + std::to_string(level) +
                                                         " or layer " + std::to_string(layer) +
                                                         " does not exist.");
    }
    ENCORE_TRY_ASSIGN(auto rows, readTexelRows(context, texture, level, layer, 8));
    std::vector<float> values(rows.size() / 2);
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::uint16_t half;
        std::memcpy(&half, rows.data() + i * 2, 2);
        values[i] = halfToFloat(half);
    }
    return values;
}

Result<std::vector<float>> readTextureR32Float(Context& context,
                                               const wgpu::Texture& texture,
                                               std::uint32_t level) {
    if (texture.GetFormat() != wgpu::TextureFormat::R32Float) {
        return makeError(ErrorCode::InvalidArgument,
                         "readTextureR32Float needs an R32Float texture.");
    }
    if (level >= texture.GetMipLevelCount()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Mip level " + std::to_string(level) + " does not exist.");
    }
    ENCORE_TRY_ASSIGN(auto rows, readTexelRows(context, texture, level, 0, 4));
    std::vector<float> values(rows.size() / 4);
    copyBytes(values.data(), rows.data(), rows.size());
    return values;
}

Result<std::vector<std::uint8_t>> readBuffer(Context& context,
                                             const wgpu::Buffer& buffer,
                                             std::uint64_t offset,
                                             std::uint64_t size) {
    if (size == 0 || size % 4 != 0 || offset % 4 != 0 || offset + size > buffer.GetSize()) {
        return makeError(ErrorCode::InvalidArgument,
                         "readBuffer range is empty, unaligned or out of bounds (offset " +
                             std::to_string(offset) + ", size " + std::to_string(size) +
                             ", buffer size " + std::to_string(buffer.GetSize()) + ").");
    }
    ENCORE_TRY(checkBufferSize(context.limits(), size, "Reading back a buffer"));
    wgpu::BufferDescriptor stagingDescriptor{};
    stagingDescriptor.label = "buffer readback";
    stagingDescriptor.size = size;
    stagingDescriptor.usage = wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::MapRead;
    wgpu::Buffer staging = context.device().CreateBuffer(&stagingDescriptor);
    wgpu::CommandEncoder encoder = context.device().CreateCommandEncoder();
    encoder.CopyBufferToBuffer(buffer, offset, staging, 0, size);
    wgpu::CommandBuffer commands = encoder.Finish();
    context.queue().Submit(1, &commands);
    return mapAndCopy(context, staging, size);
}

}  // namespace encore::gpu
