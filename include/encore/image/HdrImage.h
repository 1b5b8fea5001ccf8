#pragma once

// High-dynamic-range images: Radiance .hdr panoramas for image-based lighting, and the default
// studio environment Encore generates when no file is given.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "encore/core/Result.h"

namespace encore::image {

// Linear RGB radiance, 32-bit float, alpha dropped. An environment panorama is
// equirectangular: width = 2 * height, row 0 is straight up (+Y), and column i covers the
// longitude phi = 2 * pi * (i + 0.5) / width where a direction is
// (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)).
struct HdrImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<float> rgb;  // width * height * 3 floats, rows top to bottom.
};

// Decodes Radiance RGBE (.hdr) bytes. Refuses sizes above kMaxImageDimension.
Result<HdrImage> decodeHdr(std::span<const std::uint8_t> encoded);
Result<HdrImage> readHdr(const std::filesystem::path& path);

// The default environment: a neutral studio (sky gradient, warm ground, a small bright sun and
// two soft box lights), generated in code so `encore render MODEL` needs no file.
HdrImage makeStudioEnvironment(std::uint32_t width = 512);

// A panorama of one constant radiance (the white furnace test uses 1, 1, 1).
HdrImage makeUniformEnvironment(float r, float g, float b, std::uint32_t width = 64);

}  // namespace encore::image
