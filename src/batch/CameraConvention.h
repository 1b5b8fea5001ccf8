#pragma once

// A view's camera (camera-to-world in OpenGL's axes and the glTF world, ViewRig.h) expressed in
// another convention (CameraConvention), and back: what every written camera and every camera
// read from a --poses file goes through.
//
//   opengl   the matrix itself;
//   opencv   the camera's Y and Z axes negated (it looks along +Z with +Y down), the world kept;
//   blender  the world turned as Blender's glTF importer turns it, glTF's (x, y, z) becoming
//            (x, -z, y); Blender's camera axes are OpenGL's.

#include <array>
#include <cstdint>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "encore/batch/ViewRig.h"

namespace encore::batch {

// Camera-to-world in `convention`.
glm::dmat4 cameraToWorldIn(const glm::mat4& cameraToWorld, CameraConvention convention);

// The OpenGL, glTF-world camera-to-world of `cameraToWorld` given in `convention`.
glm::dmat4 cameraToWorldFrom(const glm::dmat4& cameraToWorld, CameraConvention convention);

// The world-to-camera matrix [R | T] in `convention` (the .npy files' 3x4): row-major, the first
// row's four values, then the second's and the third's. In the Blender convention it is the
// matrix the Objaverse-XL rendering script saves (ObjaverseCamera.h).
std::array<double, 12> worldToCameraRows(const glm::mat4& cameraToWorld,
                                         CameraConvention convention);

// A view's camera file as G-Objaverse writes one per view (--layout gobjaverse): "origin" (the
// camera's position), "x", "y", "z" (its axes in the world: the columns of camera-to-world) in
// `convention`, and "x_fov", "y_fov" (radians) for an image of `width` x `height`; an
// orthographic view has "projection": "orthographic" and "ortho_scale" instead of the fields of
// view.
nlohmann::json cameraFileJson(const ViewCamera& view,
                              CameraConvention convention,
                              std::uint32_t width,
                              std::uint32_t height);

}  // namespace encore::batch
