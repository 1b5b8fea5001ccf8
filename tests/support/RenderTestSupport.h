#pragma once

// Cameras and projections shared by the pixel tests of tests/gpu.

#include <cstdint>
#include <utility>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "encore/render/Camera.h"

namespace encore::test {

// A camera on the +Z axis (shifted by `x`) looking down -Z at z = 0, 90 degree field of view:
// at z = 0 the view spans [-3, 3] vertically, so tests can place geometry in known pixels.
inline render::Camera frontCamera(float aspect = 1.0f, float x = 0.0f) {
    return render::Camera::lookAt({x, 0.0f, 3.0f}, {x, 0.0f, 0.0f}, glm::half_pi<float>(),
                                  aspect, 0.1f, 10.0f);
}

// The pixel of a `width` x `height` image that a world point projects to.
inline std::pair<std::uint32_t, std::uint32_t> pixelOf(const render::Camera& camera,
                                                       const glm::vec3& point,
                                                       std::uint32_t width,
                                                       std::uint32_t height) {
    const glm::vec4 clip = camera.projection * camera.view * glm::vec4(point, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {static_cast<std::uint32_t>((ndc.x * 0.5f + 0.5f) * float(width)),
            static_cast<std::uint32_t>((0.5f - ndc.y * 0.5f) * float(height))};
}

}  // namespace encore::test
