#include "batch/ObjaverseCamera.h"

#include "batch/CameraConvention.h"

namespace encore::batch {

std::array<double, 12> objaverseCameraMatrix(const glm::mat4& cameraToWorld) {
    return worldToCameraRows(cameraToWorld, CameraConvention::Blender);
}

}  // namespace encore::batch
