#include "encore/render/Camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "encore/scene/SceneData.h"

namespace encore::render {

namespace {
// Front, a little to the right and above: shows three faces of a box-like model.
const glm::vec3 kFramingDirection = glm::normalize(glm::vec3(0.45f, 0.35f, 1.0f));

bool isInfinite(float farPlane) {
    return !(farPlane > 0.0f) || std::isinf(farPlane);
}

// The inverse of the rigid part of a camera node's world matrix. Orthonormalising from -Z
// (where the camera looks) and then +Y keeps the view direction exact and the horizon as close
// to the authored one as the matrix allows.
glm::mat4 rigidViewFromWorld(const glm::mat4& world) {
    const glm::vec3 origin(world[3]);
    glm::vec3 back(world[2]);
    glm::vec3 up(world[1]);
    if (glm::length(back) < 1e-20f || glm::length(up) < 1e-20f) {
        // A collapsed camera node (zero scale): nothing to orient by, look down -Z.
        return glm::translate(glm::mat4(1.0f), -origin);
    }
    back = glm::normalize(back);
    up = up - glm::dot(up, back) * back;
    if (glm::length(up) < 1e-20f) {
        up = std::abs(back.y) < 0.999f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, -1.0f);
        up = up - glm::dot(up, back) * back;
    }
    up = glm::normalize(up);
    const glm::vec3 right = glm::cross(up, back);
    // The inverse of a rotation is its transpose: the rows of the view are the camera's axes.
    glm::mat4 view(1.0f);
    for (int i = 0; i < 3; ++i) {
        view[i][0] = right[i];
        view[i][1] = up[i];
        view[i][2] = back[i];
    }
    view[3] =
        glm::vec4(-glm::dot(right, origin), -glm::dot(up, origin), -glm::dot(back, origin), 1.0f);
    return view;
}
}  // namespace

glm::mat4 perspectiveProjection(float verticalFovRadians,
                                float aspect,
                                float nearPlane,
                                float farPlane) {
    if (!isInfinite(farPlane)) {
        return glm::perspectiveRH_ZO(verticalFovRadians, aspect, nearPlane, farPlane);
    }
    // perspectiveRH_ZO as far -> infinity: z_clip = -z_view - near, w_clip = -z_view, so depth
    // = 1 - near / distance; the z row is scaled so that depth stays below 1 (see the header).
    const float tanHalfFov = std::tan(verticalFovRadians * 0.5f);
    glm::mat4 projection(0.0f);
    projection[0][0] = 1.0f / (aspect * tanHalfFov);
    projection[1][1] = 1.0f / tanHalfFov;
    projection[2][2] = -kInfiniteDepthScale;
    projection[2][3] = -1.0f;
    projection[3][2] = -nearPlane * kInfiniteDepthScale;
    return projection;
}

bool Camera::infiniteFar() const {
    return std::isinf(farPlane);
}

Camera Camera::lookAt(const glm::vec3& eye,
                      const glm::vec3& target,
                      float verticalFovRadians,
                      float aspect,
                      float nearPlane,
                      float farPlane) {
    Camera camera;
    camera.position = eye;
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (std::abs(glm::dot(glm::normalize(target - eye), up)) > 0.999f) {
        up = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    camera.view = glm::lookAtRH(eye, target, up);
    camera.projection = perspectiveProjection(verticalFovRadians, aspect, nearPlane, farPlane);
    camera.kind = ProjectionKind::Perspective;
    camera.nearPlane = nearPlane;
    camera.farPlane = isInfinite(farPlane) ? std::numeric_limits<float>::infinity() : farPlane;
    return camera;
}

Camera Camera::orthographic(const glm::mat4& cameraWorld,
                            float xmag,
                            float ymag,
                            float znear,
                            float zfar) {
    if (!(zfar > znear)) {
        zfar = znear + 1.0f;
    }
    Camera camera;
    camera.view = rigidViewFromWorld(cameraWorld);
    camera.position = glm::vec3(cameraWorld[3]);
    camera.projection = glm::orthoRH_ZO(-xmag, xmag, -ymag, ymag, znear, zfar);
    camera.kind = ProjectionKind::Orthographic;
    camera.nearPlane = znear;
    camera.farPlane = zfar;
    return camera;
}

Camera Camera::perspective(const glm::mat4& cameraWorld,
                           float yfov,
                           float aspect,
                           float znear,
                           float zfar) {
    Camera camera;
    camera.view = rigidViewFromWorld(cameraWorld);
    camera.position = glm::vec3(cameraWorld[3]);
    camera.projection = perspectiveProjection(yfov, aspect, znear, zfar);
    camera.kind = ProjectionKind::Perspective;
    camera.nearPlane = znear;
    camera.farPlane = isInfinite(zfar) ? std::numeric_limits<float>::infinity() : zfar;
    return camera;
}

Camera Camera::fromGltf(const scene::CameraData& camera,
                        const glm::mat4& world,
                        float targetAspect) {
    if (camera.projection == scene::CameraProjection::Orthographic) {
        return orthographic(world, camera.xmag, camera.ymag, camera.znear, camera.zfar);
    }
    float aspect = targetAspect;
    if (!(aspect > 0.0f)) {
        aspect = camera.aspectRatio > 0.0f ? camera.aspectRatio : 1.0f;
    }
    return perspective(world, camera.yfov, aspect, camera.znear, camera.zfar);
}

Camera Camera::framing(const scene::Bounds& bounds,
                       float aspect,
                       float yawRadians,
                       float verticalFovRadians) {
    glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    float radius = std::max(bounds.radius(), 1e-4f);
    // Bounds hold finite points only, but a box near the float range overflows its centre or
    // radius: frame the origin instead, so the camera never holds NaN or infinity.
    const bool finite = std::isfinite(center.x) && std::isfinite(center.y) &&
                        std::isfinite(center.z) && std::isfinite(radius * 4.0f);
    const scene::Bounds box = finite ? bounds : scene::Bounds{};
    if (!finite) {
        center = glm::vec3(0.0f);
        radius = 1e-4f;
    }
    const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), yawRadians, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 direction = glm::vec3(yaw * glm::vec4(kFramingDirection, 0.0f));
    // The camera basis for that direction (as lookAt builds it).
    const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), direction));
    const glm::vec3 up = glm::cross(direction, right);
    const float tanHalfY = std::tan(verticalFovRadians * 0.5f);
    const float tanHalfX = tanHalfY * aspect;
    // The distance from the centre at which every corner of the box is inside both fields of
    // view: a corner nearer the camera by `toward` needs |offset| / tan(half fov) + toward.
    float distance = 0.0f;
    if (box.empty()) {
        distance = radius / std::sin(verticalFovRadians * 0.5f);
    }
    for (int corner = 0; corner < 8 && !box.empty(); ++corner) {
        const glm::vec3 point((corner & 1) ? box.max.x : box.min.x,
                              (corner & 2) ? box.max.y : box.min.y,
                              (corner & 4) ? box.max.z : box.min.z);
        const glm::vec3 offset = point - center;
        const float toward = glm::dot(offset, direction);
        distance = std::max({distance, std::abs(glm::dot(offset, right)) / tanHalfX + toward,
                             std::abs(glm::dot(offset, up)) / tanHalfY + toward});
    }
    distance = std::max(distance * 1.05f, radius * 1e-3f);  // A small margin around the model.
    const float nearPlane = std::max(distance - radius * 1.5f, distance * 1e-3f);
    const float farPlane = distance + radius * 1.5f;
    return lookAt(center + direction * distance, center, verticalFovRadians, aspect, nearPlane,
                  farPlane);
}

}  // namespace encore::render
