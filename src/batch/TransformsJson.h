#pragma once

// transforms.json in the NeRF "synthetic" convention (the Blender scenes of Mildenhall et al.),
// which nerfstudio, instant-ngp and 3D Gaussian Splatting trainers read as it is:
//   camera_angle_x     horizontal field of view in radians;
//   frames[].file_path the image without its ".png" extension, relative to the file ("./000");
//   frames[].transform_matrix  camera-to-world, 4x4, row-major (one array per row), OpenGL camera
//                      axes (looking along -Z, +Y up).
// Beside them the pinhole intrinsics in the keys nerfstudio and instant-ngp also read (w, h,
// fl_x, fl_y, cx, cy, in pixels) so no reader has to derive them.
//
// Every frame also keeps its own intrinsics (camera_angle_x, fl_x, fl_y, cx, cy, w, h, as
// nerfstudio reads them per frame), since a batch may draw each view's field of view from a
// range; the file-level keys are written too where every frame shares them (camera_angle_x and
// the focal lengths only then). And every frame records its lighting: "environment" (the file
// relative to --environment-dir, the --environment file, or "studio"), "rotation" (degrees about
// +Y) and "intensity".

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "batch/PassImages.h"
#include "encore/batch/BatchLighting.h"
#include "encore/batch/ViewImages.h"
#include "encore/batch/ViewRig.h"

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

// With `extras`, every frame also names each pass's image ("normal_file_path": "./000_normal",
// "depth_file_path", "albedo_file_path", ...); with 16-bit depth, "depth_scale" says what one
// unit of the value is in world units, with EXR depth "depth_format" is "exr"; with
// segmentation, "segmentation_by" and "segmentation_ids" (id and name, `segmentation`).
// With `lighting`, every frame records it. "camera_convention" names the axes the matrices are
// in (CameraConvention.h: opengl, NeRF's, unless asked otherwise). An orthographic frame has no
// camera_angle_x or focal lengths: "projection": "orthographic" and "ortho_scale" (what the view
// spans across the image's larger side, in the normalised world) instead.
// What the passes' values mean when a convention differs from the default
// (docs/batch.md#conventions): "depth_kind" and "depth_unit" with --depth, "normal_space",
// "normal_kind" and "normal_format" with --normals; nothing when all are the defaults.
// "coordinates_format" with --coordinates.
void addPassConventions(nlohmann::json& json, const ExtraImages& extras);

nlohmann::json transformsJson(std::span<const ViewCamera> views,
                              std::uint32_t width,
                              std::uint32_t height,
                              const ExtraImages& extras = {},
                              double depthScale = 0.0,
                              const ModelLighting* lighting = nullptr,
                              std::span<const SegmentationName> segmentation = {},
                              CameraConvention convention = CameraConvention::OpenGl);

}  // namespace encore::batch
