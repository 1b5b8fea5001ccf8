#include "view/OrbitCamera.h"

#include <algorithm>
#include <cmath>

namespace encore::view {

namespace {
constexpr float kMaxPitch = 1.55f;      // Just short of straight down (pi / 2).
constexpr float kNearFraction = 1e-3f;  // Near plane at this fraction of the distance.
}  // namespace

OrbitCamera OrbitCamera::from(const render::Camera& camera, float distance) {
    OrbitCamera orbit;
    // The view matrix's third row is the camera's +Z (it looks along -Z).
    const glm::vec3 forward =
        -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    orbit.mDistance = distance > 0.0f && std::isfinite(distance) ? distance : 1.0f;
    orbit.mTarget = camera.position + forward * orbit.mDistance;
    orbit.mPitch =
        std::clamp(std::asin(std::clamp(-forward.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    orbit.mYaw = std::atan2(-forward.x, -forward.z);
    if (camera.kind == render::ProjectionKind::Perspective && camera.projection[1][1] > 0.0f) {
        orbit.mVerticalFov = 2.0f * std::atan(1.0f / camera.projection[1][1]);
    }
    return orbit;
}

glm::vec3 OrbitCamera::eye() const {
    // The direction from the eye to the target for this yaw and pitch, reversed.
    const glm::vec3 forward(-std::sin(mYaw) * std::cos(mPitch), -std::sin(mPitch),
                            -std::cos(mYaw) * std::cos(mPitch));
    return mTarget - forward * mDistance;
}

void OrbitCamera::orbit(float yawRadians, float pitchRadians) {
    mYaw += yawRadians;
    mPitch = std::clamp(mPitch + pitchRadians, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float right, float up) {
    const glm::vec3 forward = glm::normalize(mTarget - eye());
    const glm::vec3 rightAxis = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 upAxis = glm::cross(rightAxis, forward);
    mTarget += (rightAxis * right + upAxis * up) * mDistance;
}

void OrbitCamera::zoom(float factor) {
    if (factor > 0.0f && std::isfinite(factor)) {
        mDistance = std::clamp(mDistance * factor, 1e-6f, 1e9f);
    }
}

render::Camera OrbitCamera::camera(float aspect) const {
    return render::Camera::lookAt(eye(), mTarget, mVerticalFov, aspect, mDistance * kNearFraction,
                                  0.0f);
}

}  // namespace encore::view
