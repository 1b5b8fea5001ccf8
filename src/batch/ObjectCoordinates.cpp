#include "batch/ObjectCoordinates.h"

#include <algorithm>

#include "batch/ExrFile.h"
#include "batch/RgbaPng.h"

namespace encore::batch {

std::vector<float> objectCoordinates(const FloatStrip& strip, const glm::mat4& normalization) {
    std::vector<float> coordinates(std::size_t(strip.width) * strip.height * 4, 0.0f);
    for (std::uint32_t y = 0; y < strip.height; ++y) {
        for (std::uint32_t x = 0; x < strip.width; ++x) {
            const float* texel = strip.texel(x, y);
            const float coverage = texel[3];
            if (!(coverage > 0.0f)) {
                continue;
            }
            // Edges hold the covered samples' positions times their coverage (blended over an
            // empty background): their mean once divided.
            const glm::vec4 position(texel[0] / coverage, texel[1] / coverage, texel[2] / coverage,
                                     1.0f);
            const glm::vec3 inBox = glm::vec3(normalization * position) + 0.5f;
            float* out = &coordinates[(std::size_t(y) * strip.width + x) * 4];
            out[0] = inBox.x;
            out[1] = inBox.y;
            out[2] = inBox.z;
            out[3] = std::min(coverage, 1.0f);
        }
    }
    return coordinates;
}

Result<std::vector<std::uint8_t>> encodeCoordinates(const std::vector<float>& coordinates,
                                                    std::uint32_t width,
                                                    std::uint32_t height,
                                                    CoordinatesFormat format,
                                                    image::PngCompression compression) {
    if (format == CoordinatesFormat::Exr) {
        return encodeExrRgbaHalf(coordinates, width, height);
    }
    return encodeRgbaPng(coordinates, width, height, 16, compression);
}

}  // namespace encore::batch
