#include "HdrFiles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

namespace encore::test {
namespace {

// Radiance's shared-exponent encoding.
void appendRgbe(std::string& bytes, const glm::vec3& radiance) {
    const float largest = std::max({radiance.r, radiance.g, radiance.b});
    if (largest < 1e-32f) {
        bytes.append(4, '\0');
        return;
    }
    int exponent = 0;
    const float scale = std::frexp(largest, &exponent) * 256.0f / largest;
    bytes += char(std::uint8_t(radiance.r * scale));
    bytes += char(std::uint8_t(radiance.g * scale));
    bytes += char(std::uint8_t(radiance.b * scale));
    bytes += char(std::uint8_t(exponent + 128));
}

}  // namespace

void writeHdr(const std::filesystem::path& path,
              const glm::vec3& sky,
              const glm::vec3& ground,
              unsigned width) {
    const unsigned height = std::max(1u, width / 2);
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) +
                        " +X " + std::to_string(width) + "\n";
    for (unsigned y = 0; y < height; ++y) {
        for (unsigned x = 0; x < width; ++x) {
            appendRgbe(bytes, y < height / 2 ? sky : ground);
        }
    }
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace encore::test
