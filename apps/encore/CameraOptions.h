#pragma once

// The camera options shared by subcommands that draw a scene: a glTF camera of the file, an
// explicit viewpoint, or the automatic framing of the scene's bounds.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "encore/render/Camera.h"
#include "encore/scene/SceneData.h"

namespace encore::app {

// The vertical field of view of an explicit viewpoint without --yfov.
inline constexpr float kDefaultYfovDegrees = 45.0f;
// An explicit viewpoint without --znear puts the near plane at this fraction of the distance
// to the target: with the infinite far plane (the default) depth precision depends on the near
// plane only, and 1/1000 of the viewing distance keeps geometry just in front of the camera.
inline constexpr float kDefaultNearFraction = 1e-3f;

struct CameraOptions {
    // --camera N|NAME: the scene's N-th placed camera (SceneData::cameraInstances, depth-first
    // by node) or the first one whose camera is named NAME; a number is an index first.
    std::string camera;
    std::optional<glm::vec3> position;  // --camera-position X,Y,Z (with --target)
    std::optional<glm::vec3> target;    // --target X,Y,Z (with --camera-position)
    std::optional<float> yfovDegrees;   // --yfov, in (0, 180)
    std::optional<float> znear;         // --znear, > 0
    std::optional<float> zfar;          // --zfar, > znear
    float yawDegrees = 0.0f;  // Turns the automatic framing; set by the command (e.g. --yaw).
};

// Registers --camera, --camera-position, --target, --yfov, --znear and --zfar on `command`.
// Each value is checked as it is parsed (usage errors, exit code 2); --camera-position and
// --target need each other and exclude --camera. Negative coordinates need the = form:
// --camera-position=-1,2,3.
void addCameraOptions(CLI::App& command, CameraOptions& options);

// The camera the options ask for, for a target of `aspect` (width / height):
//  - --camera: that glTF camera at its node (render::Camera::fromGltf); --yfov (perspective
//    cameras only), --znear and --zfar replace the file's values;
//  - --camera-position and --target: a perspective lookAt with --yfov (default 45 degrees),
//    --znear (default kDefaultNearFraction of the distance) and --zfar (default: infinite);
//  - otherwise render::Camera::framing of the scene's bounds, turned by yawDegrees, with --yfov
//    (default 45 degrees); --znear and --zfar replace the distances framing chose.
// Fails with InvalidArgument (a usage error), its message starting with the scene's file, when
// the camera is not in the file (the message lists those that are), --yfov is given for an
// orthographic camera, the position equals the target, or the far plane is not beyond the
// near one.
Result<render::Camera> resolveCamera(const CameraOptions& options,
                                     const scene::SceneData& scene,
                                     float aspect);

}  // namespace encore::app
