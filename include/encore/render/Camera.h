#pragma once

#include <glm/glm.hpp>

#include "encore/scene/Bounds.h"

namespace encore::render {

// A perspective camera producing WebGPU clip space (right-handed view, depth 0..1).
struct Camera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 position{0.0f};

    static Camera lookAt(const glm::vec3& eye, const glm::vec3& target, float verticalFovRadians,
                         float aspect, float nearPlane, float farPlane);

    // Frames a bounding box: the camera looks at the box's centre from a fixed direction (front,
    // slightly right and above) at the nearest distance where all eight corners of the box lie
    // inside both fields of view (with a 5% margin). Tighter than fitting the enclosing sphere,
    // which leaves flat scenes small in the image.
    // `yawRadians` turns the viewpoint around the vertical axis through the centre.
    static Camera framing(const scene::Bounds& bounds, float aspect, float yawRadians = 0.0f);
};

}  // namespace encore::render
