#pragma once

// The camera matrix the Objaverse-XL rendering script (scripts/rendering/blender_script.py,
// get_3x4_RT_matrix_from_blender, taken from Zero123) saves as 000.npy beside each view:
//   RT = [R | T], 3x4, float64, with R = the camera's rotation transposed and T = -R location:
// world-to-camera, in Blender's camera axes (x right, y up, looking along -z: OpenGL's, not
// OpenCV's; that script leaves out the flip its source had) and Blender's world, which is +Z up:
// Blender's glTF importer turns glTF's +Y up into +Z and glTF's +Z into -Y, so a point (x, y, z)
// of the model's glTF frame lies at (x, -z, y) in the world of those matrices.
//
// transforms.json keeps the glTF frame (+Y up); these matrices are the same cameras in the
// Blender frame that Objaverse-trained code (Zero123's elevation from z, for one) expects.

#include <array>

#include <glm/glm.hpp>

namespace encore::batch {

// Row-major: the first row's four values, then the second's and the third's.
std::array<double, 12> objaverseCameraMatrix(const glm::mat4& cameraToWorld);

}  // namespace encore::batch
