#pragma once

// --poses FILE: the cameras of an existing dataset, read so that a batch renders exactly them.
// Three forms, told apart by the content:
//   a transforms.json, as `encore batch` writes it (TransformsJson.h) or NeRF's synthetic scenes
//     are: frames[].transform_matrix (camera-to-world, 4x4, one array per row), each frame's
//     camera_angle_x or the file's, and Encore's "projection" and "ortho_scale" where present;
//     in the axes its "camera_convention" names (else `convention`, else OpenGL's, NeRF's);
//   a JSON list: each entry a 4x4 camera-to-world matrix (rows), or an object as a frame above;
//     in `convention`'s axes, else OpenGL's;
//   a .npy stack (NumPy's format, little-endian float32 or float64, C order) of shape (N, 3, 4),
//     (N, 4, 4), (3, 4) or (4, 4): world-to-camera matrices [R | T], as `--layout objaverse`
//     writes each view's 000.npy, in `convention`'s axes, else Blender's (the Objaverse scripts').
// Cameras are in the normalised world (the unit box) unless --no-normalize, as written. What a
// file does not say (a .npy's field of view, a list entry's) comes from `rig`: its projection,
// ortho scale and field of view (which must then be one value, not a range).
//
// Every error is InvalidArgument and names `shown` (the option), the file and, where it is about
// one camera, its index: "--poses 'cams.json': frame 3: transform_matrix is not 4x4 numbers."

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "encore/batch/ViewRig.h"
#include "encore/core/Result.h"

namespace encore::batch {

// At most this many cameras (as many as --views takes).
inline constexpr std::size_t kMaxPoses = 10'000;

Result<std::vector<ViewCamera>> readPoseFile(const std::filesystem::path& path,
                                             std::string_view shown,
                                             std::optional<CameraConvention> convention,
                                             const ViewRigOptions& rig);

}  // namespace encore::batch
