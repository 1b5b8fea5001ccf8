#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "encore/scene/SceneData.h"

namespace encore::scene {
struct CameraData;
}  // namespace encore::scene

namespace encore::render {

enum class ProjectionKind : std::uint8_t { Perspective, Orthographic };

// The scale applied to the depth of an infinite perspective projection: a point at distance d
// gets depth (1 - n / d) * kInfiniteDepthScale instead of 1 - n / d. Without it, points farther
// than about 2^24 near-plane distances round to depth 1 and fail the depth test (compare Less,
// cleared to 1); with it even the points at infinity stay 2^-19 (32 float steps) below 1, which
// absorbs the rounding of the vertex transform. Depth precision is unaffected.
inline constexpr float kInfiniteDepthScale = 1.0f - 1.0f / 524288.0f;

// A right-handed perspective projection onto WebGPU's clip space (depth 0 at `nearPlane`, 1 at
// `farPlane`). `farPlane` <= 0 or infinite gives the infinite form (the limit as far -> infinity,
// its depth scaled by kInfiniteDepthScale), whose depth tends to 1 at infinity. A finite far
// plane gives exactly glm::perspectiveRH_ZO.
glm::mat4 perspectiveProjection(float verticalFovRadians,
                                float aspect,
                                float nearPlane,
                                float farPlane);

// The vertical field of view of Camera::framing unless told otherwise (45 degrees).
inline constexpr float kFramingFovRadians = glm::radians(45.0f);

// A camera producing WebGPU clip space (right-handed view, depth 0..1; draw with depth compare
// Less and clear depth to 1). Besides the matrices it records the kind of projection and its
// clip distances, for code that needs them (frustum tests, depth linearisation).
struct Camera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 position{0.0f};
    ProjectionKind kind = ProjectionKind::Perspective;
    float nearPlane = 0.0f;
    float farPlane = 0.0f;  // +infinity for an infinite perspective projection.

    glm::mat4 viewProjection() const { return projection * view; }
    bool infiniteFar() const;

    // A perspective camera at `eye` looking at `target` with +Y up (-Z up when looking straight
    // up or down). `farPlane` <= 0 or infinite: an infinite far plane (perspectiveProjection).
    static Camera lookAt(const glm::vec3& eye,
                         const glm::vec3& target,
                         float verticalFovRadians,
                         float aspect,
                         float nearPlane,
                         float farPlane);

    // Cameras placed by a node: the camera looks along the node's -Z axis with its +Y axis up,
    // and the view matrix is the inverse of `cameraWorld`. A world matrix with scale or shear is
    // made rigid first (its axes orthonormalised, keeping -Z and then +Y), so the view never
    // scales the scene; glTF gives camera nodes no meaningful scale.
    //
    // Orthographic: the view spans [-xmag, xmag] x [-ymag, ymag] and depth 0..1 maps
    // [znear, zfar], as glTF's orthographic matrix does. zfar must exceed znear (glTF requires
    // it); otherwise zfar is taken as znear + 1 so that the matrix stays finite.
    static Camera orthographic(const glm::mat4& cameraWorld,
                               float xmag,
                               float ymag,
                               float znear,
                               float zfar);
    // Perspective: `zfar` 0 (or <= 0, or infinite) gives the infinite projection.
    static Camera perspective(const glm::mat4& cameraWorld,
                              float yfov,
                              float aspect,
                              float znear,
                              float zfar);

    // A glTF camera placed at `world` for a target of `targetAspect` (width / height).
    // Perspective keeps the file's yfov and always uses the target's aspect ratio: the file's
    // aspectRatio, when given, only says what the author framed, and glTF tells clients not to
    // stretch the picture to it (they may letterbox instead). Encore does not letterbox, so a
    // target wider than the file's aspect ratio shows more on the sides, a narrower one less.
    // The file's aspectRatio is used only when `targetAspect` is not positive.
    // Orthographic uses xmag and ymag as given (glTF: the picture is stretched when xmag / ymag
    // differs from the target's aspect ratio).
    static Camera fromGltf(const scene::CameraData& camera,
                           const glm::mat4& world,
                           float targetAspect);

    // Frames a bounding box: the camera looks at the box's centre from a fixed direction (front,
    // slightly right and above) at the nearest distance where all eight corners of the box lie
    // inside both fields of view (with a 5% margin). Tighter than fitting the enclosing sphere,
    // which leaves flat scenes small in the image.
    // `yawRadians` turns the viewpoint around the vertical axis through the centre.
    static Camera framing(const scene::Bounds& bounds,
                          float aspect,
                          float yawRadians = 0.0f,
                          float verticalFovRadians = kFramingFovRadians);
};

}  // namespace encore::render
