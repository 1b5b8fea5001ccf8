#include "batch/ObjaverseCamera.h"

namespace encore::batch {

std::array<double, 12> objaverseCameraMatrix(const glm::mat4& cameraToWorld) {
    // From glTF's world to Blender's: (x, y, z) -> (x, -z, y).
    const glm::dmat3 gltfToBlender(glm::dvec3(1.0, 0.0, 0.0),    // Column 0: glTF's +X.
                                   glm::dvec3(0.0, 0.0, 1.0),    // Column 1: glTF's +Y is +Z.
                                   glm::dvec3(0.0, -1.0, 0.0));  // Column 2: glTF's +Z is -Y.
    const glm::dmat3 rotation = gltfToBlender * glm::dmat3(glm::dmat4(cameraToWorld));
    const glm::dvec3 location = gltfToBlender * glm::dvec3(glm::dvec4(cameraToWorld[3]));
    // The camera's frame is orthonormal: its inverse rotation is its transpose.
    const glm::dmat3 worldToCamera = glm::transpose(rotation);
    const glm::dvec3 translation = -(worldToCamera * location);
    std::array<double, 12> rows{};
    for (int row = 0; row < 3; ++row) {
        for (int column = 0; column < 3; ++column) {
            rows[4 * row + column] = worldToCamera[column][row];  // glm: [column][row].
        }
        rows[4 * row + 3] = translation[row];
    }
    return rows;
}

}  // namespace encore::batch
