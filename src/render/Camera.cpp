#include "encore/render/Camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace encore::render {

namespace {
constexpr float kFramingFov = glm::radians(45.0f);
// Front, a little to the right and above: shows three faces of a box-like model.
const glm::vec3 kFramingDirection = glm::normalize(glm::vec3(0.45f, 0.35f, 1.0f));
}  // namespace

Camera Camera::lookAt(const glm::vec3& eye, const glm::vec3& target, float verticalFovRadians,
                      float aspect, float nearPlane, float farPlane) {
    Camera camera;
    camera.position = eye;
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (std::abs(glm::dot(glm::normalize(target - eye), up)) > 0.999f) {
        up = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    camera.view = glm::lookAtRH(eye, target, up);
    camera.projection = glm::perspectiveRH_ZO(verticalFovRadians, aspect, nearPlane, farPlane);
    return camera;
}

Camera Camera::framing(const scene::Bounds& bounds, float aspect, float yawRadians) {
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float radius = std::max(bounds.radius(), 1e-4f);
    // Fit the sphere in the narrower of the two fields of view.
    const float horizontalFov = 2.0f * std::atan(std::tan(kFramingFov * 0.5f) * aspect);
    const float fov = std::min(kFramingFov, horizontalFov);
    const float distance = radius / std::sin(fov * 0.5f) * 1.02f;
    const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), yawRadians, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 direction = glm::vec3(yaw * glm::vec4(kFramingDirection, 0.0f));
    const float nearPlane = std::max(distance - radius * 1.5f, distance * 1e-3f);
    const float farPlane = distance + radius * 1.5f;
    return lookAt(center + direction * distance, center, kFramingFov, aspect, nearPlane,
                  farPlane);
}

}  // namespace encore::render
