#pragma once

// Copies GPU data back to the CPU, blocking until it is available. Used for headless output and
// for tests; not meant for per-frame use.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/ImageCodec.h"

namespace encore::gpu {

// Texture-to-buffer copies lay rows out kCopyRowAlignment bytes apart at least (WebGPU's
// bytesPerRow alignment): paddedRowBytes is the bytesPerRow of a copy of rows of `rowBytes`.
inline constexpr std::uint32_t kCopyRowAlignment = 256;
constexpr std::uint32_t paddedRowBytes(std::uint32_t rowBytes) {
    return (rowBytes + kCopyRowAlignment - 1) / kCopyRowAlignment * kCopyRowAlignment;
}
// Copies `rows` rows of `rowBytes` bytes from `padded`, where they lie paddedRowBytes(rowBytes)
// apart (a mapped read-back buffer), to `packed`, where they follow each other.
void unpadRows(const std::uint8_t* padded,
               std::uint32_t rowBytes,
               std::uint32_t rows,
               std::uint8_t* packed);

// An IEEE half float's value (RGBA16Float texels).
float halfToFloat(std::uint16_t half);

// Reads mip level 0 of a 2D texture with CopySrc usage. Supported formats: RGBA8Unorm(Srgb) and
// BGRA8Unorm(Srgb); the result is RGBA either way (bytes as stored, no colour conversion).
Result<image::ImageRgba8> readTexture(Context& context, const wgpu::Texture& texture);

// Same for one mip level (its size is the level-0 size halved `level` times, at least 1).
Result<image::ImageRgba8> readTextureLevel(Context& context,
                                           const wgpu::Texture& texture,
                                           std::uint32_t level);

// Reads one mip level and array layer of an RGBA16Float texture (CopySrc) as RGBA floats, rows
// top to bottom: HDR render targets and environment maps, for tests and tools.
Result<std::vector<float>> readTextureRgba16Float(Context& context,
                                                  const wgpu::Texture& texture,
                                                  std::uint32_t level = 0,
                                                  std::uint32_t layer = 0);

// Reads one mip level of an R32Float texture (CopySrc), rows top to bottom: depth pyramids.
Result<std::vector<float>> readTextureR32Float(Context& context,
                                               const wgpu::Texture& texture,
                                               std::uint32_t level);

// Reads `size` bytes at `offset` of a buffer with CopySrc usage (offset and size multiples of 4).
Result<std::vector<std::uint8_t>> readBuffer(Context& context,
                                             const wgpu::Buffer& buffer,
                                             std::uint64_t offset,
                                             std::uint64_t size);

}  // namespace encore::gpu
