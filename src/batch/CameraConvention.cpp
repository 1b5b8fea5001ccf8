#include "batch/CameraConvention.h"

namespace encore::batch {
namespace {

// glTF's world into Blender's: (x, y, z) -> (x, -z, y), a rotation about +X.
const glm::dmat4 kGltfToBlender(glm::dvec4(1.0, 0.0, 0.0, 0.0),   // Column 0: glTF's +X.
                                glm::dvec4(0.0, 0.0, 1.0, 0.0),   // Column 1: glTF's +Y is +Z.
                                glm::dvec4(0.0, -1.0, 0.0, 0.0),  // Column 2: glTF's +Z is -Y.
                                glm::dvec4(0.0, 0.0, 0.0, 1.0));
// OpenGL's camera axes into OpenCV's and back (its own inverse).
const glm::dmat4 kFlipYZ(glm::dvec4(1.0, 0.0, 0.0, 0.0),
                         glm::dvec4(0.0, -1.0, 0.0, 0.0),
                         glm::dvec4(0.0, 0.0, -1.0, 0.0),
                         glm::dvec4(0.0, 0.0, 0.0, 1.0));

}  // namespace

glm::dmat4 cameraToWorldIn(const glm::mat4& cameraToWorld, CameraConvention convention) {
    const glm::dmat4 matrix(cameraToWorld);
    switch (convention) {
        case CameraConvention::OpenGl:
            return matrix;
        case CameraConvention::OpenCv:
            return matrix * kFlipYZ;
        case CameraConvention::Blender:
            return kGltfToBlender * matrix;
    }
    return matrix;
}

glm::dmat4 cameraToWorldFrom(const glm::dmat4& cameraToWorld, CameraConvention convention) {
    switch (convention) {
        case CameraConvention::OpenGl:
            return cameraToWorld;
        case CameraConvention::OpenCv:
            return cameraToWorld * kFlipYZ;
        case CameraConvention::Blender:
            return glm::transpose(kGltfToBlender) * cameraToWorld;  // A rotation's inverse.
    }
    return cameraToWorld;
}

std::array<double, 12> worldToCameraRows(const glm::mat4& cameraToWorld,
                                         CameraConvention convention) {
    const glm::dmat4 toWorld = cameraToWorldIn(cameraToWorld, convention);
    const glm::dmat3 rotation(toWorld);
    const glm::dvec3 location(toWorld[3]);
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

nlohmann::json cameraFileJson(const ViewCamera& view,
                              CameraConvention convention,
                              std::uint32_t width,
                              std::uint32_t height) {
    const glm::dmat4 cameraToWorld = cameraToWorldIn(view.cameraToWorld, convention);
    const auto column = [&](int index) {
        return nlohmann::json::array(
            {cameraToWorld[index].x, cameraToWorld[index].y, cameraToWorld[index].z});
    };
    nlohmann::json json = {
        {"origin", column(3)}, {"x", column(0)}, {"y", column(1)}, {"z", column(2)}};
    if (view.projection == Projection::Orthographic) {
        json["projection"] = "orthographic";
        json["ortho_scale"] = double(view.orthoScale);
    } else {
        const float aspect = float(width) / float(height);
        json["x_fov"] = double(view.horizontalFovRadians);
        json["y_fov"] = double(verticalFov(view.horizontalFovRadians, aspect));
    }
    return json;
}

}  // namespace encore::batch
