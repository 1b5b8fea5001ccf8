#include "batch/NormalConventions.h"

#include <algorithm>
#include <cmath>

#include "batch/CameraConvention.h"
#include "batch/ExrFile.h"
#include "batch/RgbaPng.h"

namespace encore::batch {

glm::dmat3 normalRotation(const ViewCamera& view, NormalSpace space, CameraConvention convention) {
    if (space == NormalSpace::World) {
        return glm::dmat3(1.0);
    }
    // Blender's convention turns the world, not the camera: its camera axes are OpenGL's, and
    // a camera-space normal does not depend on the world's axes.
    const CameraConvention axes = convention == CameraConvention::OpenCv ? CameraConvention::OpenCv
                                                                         : CameraConvention::OpenGl;
    const glm::dmat4 cameraToWorld = cameraToWorldIn(view.cameraToWorld, axes);
    // The columns are the camera's axes in the world; normalised in case the rig's matrix
    // carries a scale.
    const glm::dmat3 axesInWorld(glm::normalize(glm::dvec3(cameraToWorld[0])),
                                 glm::normalize(glm::dvec3(cameraToWorld[1])),
                                 glm::normalize(glm::dvec3(cameraToWorld[2])));
    return glm::transpose(axesInWorld);
}

std::vector<float> normalVectors(const FloatStrip& strip, const glm::dmat3& rotation) {
    return coveredTexels(strip, [&](const float* texel, float coverage) {
        const glm::dvec3 mapped = glm::dvec3(texel[0], texel[1], texel[2]) / double(coverage);
        const glm::dvec3 n = mapped * 2.0 - 1.0;
        const double length = glm::length(n);
        if (!(length > 1e-6)) {
            return std::optional<glm::vec3>();
        }
        return std::optional<glm::vec3>(rotation * (n / length));
    });
}

std::vector<float> mappedNormals(const std::vector<float>& normals) {
    std::vector<float> mapped(normals.size(), 0.0f);
    for (std::size_t i = 0; i < normals.size(); i += 4) {
        if (normals[i + 3] == 0.0f) {
            continue;  // Empty pixels stay 0 in every channel, as the 8-bit pass's background is.
        }
        for (std::size_t c = 0; c < 3; ++c) {
            mapped[i + c] = normals[i + c] * 0.5f + 0.5f;
        }
        mapped[i + 3] = normals[i + 3];
    }
    return mapped;
}

Result<std::vector<std::uint8_t>> encodeNormals(const std::vector<float>& normals,
                                                std::uint32_t width,
                                                std::uint32_t height,
                                                NormalFormat format,
                                                image::PngCompression compression) {
    if (format == NormalFormat::Exr) {
        return encodeExrRgbaHalf(normals, width, height);
    }
    return encodeRgbaPng(mappedNormals(normals), width, height,
                         format == NormalFormat::Png16 ? 16 : 8, compression);
}

}  // namespace encore::batch
