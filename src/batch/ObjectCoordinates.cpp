#include "batch/ObjectCoordinates.h"

#include <algorithm>

#include "batch/ExrFile.h"
#include "batch/RgbaPng.h"

namespace encore::batch {

std::vector<float> objectCoordinates(const FloatStrip& strip, const glm::mat4& normalization) {
    return coveredTexels(strip, [&](const float* texel, float coverage) {
        // Edges hold the covered samples' positions times their coverage (blended over an empty
        // background): their mean once divided.
        const glm::vec4 position(texel[0] / coverage, texel[1] / coverage, texel[2] / coverage,
                                 1.0f);
        return std::optional<glm::vec3>(glm::vec3(normalization * position) + 0.5f);
    });
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
