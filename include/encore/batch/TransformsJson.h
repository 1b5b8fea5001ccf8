#pragma once

// transforms.json in the NeRF "synthetic" convention (the Blender scenes of Mildenhall et al.),
// which nerfstudio, instant-ngp and 3D Gaussian Splatting trainers read as it is:
//   camera_angle_x     horizontal field of view in radians;
//   frames[].file_path the image without its ".png" extension, relative to the file ("./000");
//   frames[].transform_matrix  camera-to-world, 4x4, row-major (one array per row), OpenGL camera
//                      axes (looking along -Z, +Y up).
// Beside them the pinhole intrinsics in the keys nerfstudio and instant-ngp also read (w, h,
// fl_x, fl_y, cx, cy, in pixels) so no reader has to derive them.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace encore::batch {

struct PinholeIntrinsics {
    double width = 0.0;
    double height = 0.0;
    double focalX = 0.0;  // Pixels.
    double focalY = 0.0;
    double centerX = 0.0;
    double centerY = 0.0;
};

// Square pixels, the principal point in the image centre.
PinholeIntrinsics intrinsicsFor(std::uint32_t width,
                                std::uint32_t height,
                                float horizontalFovRadians);

// The name of view `index`'s image without extension: "000", "001", ... (at least three digits).
std::string viewStem(std::size_t index);
// What the normal image of a view adds to its stem: "000_normal".
inline constexpr const char* kNormalSuffix = "_normal";

// With `normals`, every frame also names its normal image in "normal_file_path" ("./000_normal").
nlohmann::json transformsJson(float horizontalFovRadians,
                              std::uint32_t width,
                              std::uint32_t height,
                              std::span<const glm::mat4> cameraToWorld,
                              bool normals = false);

}  // namespace encore::batch
