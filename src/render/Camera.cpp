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
    const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), yawRadians, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 direction = glm::vec3(yaw * glm::vec4(kFramingDirection, 0.0f));
    // The camera basis for that direction (as lookAt builds it).
    const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), direction));
    const glm::vec3 up = glm::cross(direction, right);
    const float tanHalfY = std::tan(kFramingFov * 0.5f);
    const float tanHalfX = tanHalfY * aspect;
    // The distance from the centre at which every corner of the box is inside both fields of
    // view: a corner nearer the camera by `toward` needs |offset| / tan(half fov) + toward.
    float distance = 0.0f;
    if (bounds.empty()) {
        distance = radius / std::sin(kFramingFov * 0.5f);
    }
    for (int corner = 0; corner < 8 && !bounds.empty(); ++corner) {
        const glm::vec3 point((corner & 1) ? bounds.max.x : bounds.min.x,
                              (corner & 2) ? bounds.max.y : bounds.min.y,
                              (corner & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 offset = point - center;
        const float toward = glm::dot(offset, direction);
        distance = std::max({distance, std::abs(glm::dot(offset, right)) / tanHalfX + toward,
                             std::abs(glm::dot(offset, up)) / tanHalfY + toward});
    }
    distance = std::max(distance * 1.05f, radius * 1e-3f);  // A small margin around the model.
    const float nearPlane = std::max(distance - radius * 1.5f, distance * 1e-3f);
    const float farPlane = distance + radius * 1.5f;
    return lookAt(center + direction * distance, center, kFramingFov, aspect, nearPlane,
                  farPlane);
}

}  // namespace encore::render
