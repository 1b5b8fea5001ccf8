#pragma once

// A camera that orbits a point: the viewer's mouse and key controls turn, pan and zoom it.
// It starts from any render::Camera (the one `encore render` would use), keeping its eye, its
// viewing direction and its vertical field of view, so the first frame matches that camera.

#include <glm/glm.hpp>

#include "encore/render/Camera.h"

namespace encore::view {

class OrbitCamera {
  public:
    // Orbits the point `distance` ahead of `camera`'s eye (pass the distance to what it looks
    // at). An orthographic camera becomes a perspective one of 45 degrees.
    static OrbitCamera from(const render::Camera& camera, float distance);

    // Turns the eye around the target: yaw about +Y, pitch up and down (kept short of the poles).
    void orbit(float yawRadians, float pitchRadians);
    // Moves eye and target together, in fractions of the distance along the view's right and up.
    void pan(float right, float up);
    // Multiplies the distance to the target (below 1: closer).
    void zoom(float factor);

    render::Camera camera(float aspect) const;
    glm::vec3 eye() const;
    const glm::vec3& target() const { return mTarget; }
    float distance() const { return mDistance; }

  private:
    glm::vec3 mTarget{0.0f};
    float mDistance = 1.0f;
    float mYaw = 0.0f;    // Around +Y; 0 looks along -Z.
    float mPitch = 0.0f;  // Positive looks down on the target.
    float mVerticalFov = glm::radians(45.0f);
};

}  // namespace encore::view
