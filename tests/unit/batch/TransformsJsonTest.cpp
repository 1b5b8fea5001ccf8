#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "batch/TransformsJson.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

TEST(TransformsJsonTest, SyntheticNerfLayout) {
    ViewRigOptions options;
    options.views = 3;
    const auto views = viewCameras(options);
    const float fov = glm::radians(options.horizontalFovDegrees.min);
    const nlohmann::json json = transformsJson(views, 512, 256);
    EXPECT_NEAR(json["camera_angle_x"].get<double>(), fov, 1e-6);
    ASSERT_EQ(json["frames"].size(), 3u);
    EXPECT_EQ(json["frames"][0]["file_path"], "./000");
    EXPECT_EQ(json["frames"][2]["file_path"], "./002");
    // Row-major: the translation is the last column of the first three rows.
    const auto& matrix = json["frames"][1]["transform_matrix"];
    ASSERT_EQ(matrix.size(), 4u);
    for (int row = 0; row < 4; ++row) {
        ASSERT_EQ(matrix[row].size(), 4u);
        for (int column = 0; column < 4; ++column) {
            EXPECT_FLOAT_EQ(matrix[row][column].get<float>(), views[1].cameraToWorld[column][row]);
        }
    }
    EXPECT_FLOAT_EQ(matrix[0][3].get<float>(), views[1].cameraToWorld[3].x);
    EXPECT_EQ(matrix[3], nlohmann::json::parse("[0.0, 0.0, 0.0, 1.0]"));
    EXPECT_EQ(json["w"], 512);
    EXPECT_EQ(json["h"], 256);
    EXPECT_NEAR(json["fl_x"].get<double>(), 256.0 / std::tan(0.5 * fov), 1e-3);
    EXPECT_EQ(json["fl_x"], json["fl_y"]);
    EXPECT_EQ(json["cx"], 256.0);
    EXPECT_EQ(json["cy"], 128.0);
    // Every frame keeps the intrinsics too.
    for (const auto& frame : json["frames"]) {
        for (const char* key : {"camera_angle_x", "fl_x", "fl_y", "cx", "cy", "w", "h"}) {
            EXPECT_EQ(frame[key], json[key]) << key;
        }
        EXPECT_FALSE(frame.contains("environment"));  // No lighting given.
    }
}

// Fields of view drawn per view: each frame has its own focal length, and the file-level
// camera_angle_x and focal lengths are left out (no frame shares them), the size and principal
// point stay.
TEST(TransformsJsonTest, FramesKeepTheirOwnIntrinsics) {
    ViewRigOptions options;
    options.views = 4;
    options.horizontalFovDegrees = ValueRange(30.0f, 70.0f);
    const auto views = viewCameras(options, "model");
    const nlohmann::json json = transformsJson(views, 64, 32);
    EXPECT_FALSE(json.contains("camera_angle_x"));
    EXPECT_FALSE(json.contains("fl_x"));
    EXPECT_EQ(json["w"], 64);
    EXPECT_EQ(json["cx"], 32.0);
    EXPECT_EQ(json["cy"], 16.0);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const auto& frame = json["frames"][i];
        EXPECT_NEAR(frame["camera_angle_x"].get<double>(), views[i].horizontalFovRadians, 1e-7);
        EXPECT_NEAR(frame["fl_x"].get<double>(),
                    32.0 / std::tan(0.5 * double(views[i].horizontalFovRadians)), 1e-9);
        EXPECT_EQ(frame["fl_y"], frame["fl_x"]);
        EXPECT_EQ(frame["w"], 64);
        EXPECT_EQ(frame["h"], 32);
    }
    EXPECT_NE(json["frames"][0]["fl_x"], json["frames"][1]["fl_x"]);
}

TEST(TransformsJsonTest, EveryFrameRecordsItsLighting) {
    const std::vector<ViewCamera> views(2, ViewCamera{glm::mat4(1.0f), 1.0f});
    ModelLighting lighting;
    lighting.environment = "skies/noon.hdr";
    lighting.rotationDegrees = 123.5f;
    lighting.intensity = 0.75f;
    const nlohmann::json json = transformsJson(views, 8, 8, {}, 0.0, &lighting);
    for (const auto& frame : json["frames"]) {
        EXPECT_EQ(frame["environment"], "skies/noon.hdr");
        EXPECT_EQ(frame["rotation"], 123.5);
        EXPECT_EQ(frame["intensity"], 0.75);
    }
}

TEST(TransformsJsonTest, NormalAndDepthImagesAreNamedPerFrame) {
    const std::vector<ViewCamera> views(2, ViewCamera{glm::mat4(1.0f), 1.0f});
    const nlohmann::json plain = transformsJson(views, 8, 8);
    EXPECT_FALSE(plain["frames"][0].contains("normal_file_path"));
    EXPECT_FALSE(plain.contains("depth_scale"));
    const nlohmann::json withNormals = transformsJson(views, 8, 8, {.normals = true});
    EXPECT_EQ(withNormals["frames"][1]["normal_file_path"], "./001_normal");
    EXPECT_FALSE(withNormals["frames"][1].contains("depth_file_path"));
    const nlohmann::json withDepth = transformsJson(views, 8, 8, {.depth = true}, 0.5);
    EXPECT_EQ(withDepth["frames"][0]["depth_file_path"], "./000_depth");
    EXPECT_EQ(withDepth["depth_scale"], 0.5);
}

TEST(TransformsJsonTest, ViewStemsHaveAtLeastThreeDigits) {
    EXPECT_EQ(viewStem(0), "000");
    EXPECT_EQ(viewStem(42), "042");
    EXPECT_EQ(viewStem(1234), "1234");
    EXPECT_EQ(viewStem(7, ViewImage::Normal), "007_normal");
    EXPECT_EQ(viewStem(7, ViewImage::Depth), "007_depth");
}

}  // namespace
}  // namespace encore::batch
