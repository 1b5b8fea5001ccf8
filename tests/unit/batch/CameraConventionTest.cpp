// --camera-convention: the axes of a written camera, and their way back (issue 50).

#include <gtest/gtest.h>

#include <cmath>

#include "batch/CameraConvention.h"
#include "batch/ObjaverseCamera.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

constexpr double kEpsilon = 1e-6;

void expectNear(const glm::dvec3& a, const glm::dvec3& b) {
    EXPECT_NEAR(a.x, b.x, kEpsilon);
    EXPECT_NEAR(a.y, b.y, kEpsilon);
    EXPECT_NEAR(a.z, b.z, kEpsilon);
}

// A camera in front of the model (+Z) at height 0, looking at the origin.
const glm::mat4 kFront = lookAtCameraToWorld({0.0f, 0.0f, 2.0f}, glm::vec3(0.0f));

TEST(CameraConventionTest, OpenGlLooksAlongMinusZWithYUp) {
    const glm::dmat4 m = cameraToWorldIn(kFront, CameraConvention::OpenGl);
    expectNear(glm::dvec3(m[2]), {0.0, 0.0, 1.0});  // -Z looks at the origin: +Z points back.
    expectNear(glm::dvec3(m[1]), {0.0, 1.0, 0.0});  // Up.
    expectNear(glm::dvec3(m[0]), {1.0, 0.0, 0.0});  // Right.
    expectNear(glm::dvec3(m[3]), {0.0, 0.0, 2.0});
}

TEST(CameraConventionTest, OpenCvLooksAlongPlusZWithYDown) {
    const glm::dmat4 m = cameraToWorldIn(kFront, CameraConvention::OpenCv);
    expectNear(glm::dvec3(m[2]), {0.0, 0.0, -1.0});  // +Z looks at the origin.
    expectNear(glm::dvec3(m[1]), {0.0, -1.0, 0.0});  // +Y down.
    expectNear(glm::dvec3(m[0]), {1.0, 0.0, 0.0});   // +X right.
    expectNear(glm::dvec3(m[3]), {0.0, 0.0, 2.0});   // The world is glTF's.
}

TEST(CameraConventionTest, BlenderTurnsTheWorldToZUp) {
    const glm::dmat4 m = cameraToWorldIn(kFront, CameraConvention::Blender);
    expectNear(glm::dvec3(m[3]), {0.0, -2.0, 0.0});  // glTF's front (+Z) is Blender's -Y.
    expectNear(glm::dvec3(m[1]), {0.0, 0.0, 1.0});   // Up is +Z.
    expectNear(glm::dvec3(m[2]), {0.0, -1.0, 0.0});  // Looking along -Z: towards +Y.
    expectNear(glm::dvec3(m[0]), {1.0, 0.0, 0.0});
}

TEST(CameraConventionTest, EveryConventionReadsBackExactly) {
    const glm::mat4 view = lookAtCameraToWorld({0.3f, 1.1f, -0.7f}, glm::vec3(0.0f));
    for (const CameraConvention convention :
         {CameraConvention::OpenGl, CameraConvention::OpenCv, CameraConvention::Blender}) {
        const glm::mat4 back =
            glm::mat4(cameraToWorldFrom(cameraToWorldIn(view, convention), convention));
        EXPECT_EQ(back, view) << int(convention);
    }
}

TEST(CameraConventionTest, BlenderRowsAreTheObjaverseMatrix) {
    const glm::mat4 view = lookAtCameraToWorld({0.3f, 1.1f, -0.7f}, glm::vec3(0.0f));
    EXPECT_EQ(worldToCameraRows(view, CameraConvention::Blender), objaverseCameraMatrix(view));
    // OpenCV's world-to-camera puts the origin in front of the camera: +Z depth.
    const std::array<double, 12> rows = worldToCameraRows(view, CameraConvention::OpenCv);
    EXPECT_NEAR(rows[11], glm::length(glm::vec3(view[3])), 1e-6);
    EXPECT_NEAR(rows[3], 0.0, 1e-6);
    EXPECT_NEAR(rows[7], 0.0, 1e-6);
}

// G-Objaverse's camera file: the camera's position and axes (OpenCV's: +Z towards the model, +Y
// down) and both fields of view.
TEST(CameraConventionTest, CameraFilesHoldTheAxesAndFieldsOfView) {
    ViewCamera view;
    view.cameraToWorld = kFront;
    view.horizontalFovRadians = 0.6911f;
    const nlohmann::json file = cameraFileJson(view, CameraConvention::OpenCv, 512, 256);
    EXPECT_EQ(file["origin"], nlohmann::json::array({0.0, 0.0, 2.0}));
    EXPECT_EQ(file["x"], nlohmann::json::array({1.0, 0.0, 0.0}));
    EXPECT_EQ(file["y"], nlohmann::json::array({0.0, -1.0, 0.0}));
    EXPECT_EQ(file["z"], nlohmann::json::array({0.0, 0.0, -1.0}));
    EXPECT_NEAR(file["x_fov"].get<double>(), 0.6911, 1e-6);
    EXPECT_NEAR(file["y_fov"].get<double>(), 2.0 * std::atan(std::tan(0.6911 / 2.0) / 2.0), 1e-6);
    view.projection = Projection::Orthographic;
    view.orthoScale = 1.35f;
    const nlohmann::json orthographic = cameraFileJson(view, CameraConvention::OpenGl, 64, 64);
    EXPECT_EQ(orthographic["projection"], "orthographic");
    EXPECT_FALSE(orthographic.contains("x_fov"));
    EXPECT_EQ(orthographic["z"], nlohmann::json::array({0.0, 0.0, 1.0}));
}

}  // namespace
}  // namespace encore::batch
