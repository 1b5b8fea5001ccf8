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
    const auto views = viewMatrices(options);
    const float fov = glm::radians(options.horizontalFovDegrees);
    const nlohmann::json json = transformsJson(fov, 512, 256, views);
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
            EXPECT_FLOAT_EQ(matrix[row][column].get<float>(), views[1][column][row]);
        }
    }
    EXPECT_FLOAT_EQ(matrix[0][3].get<float>(), views[1][3].x);
    EXPECT_EQ(matrix[3], nlohmann::json::parse("[0.0, 0.0, 0.0, 1.0]"));
    EXPECT_EQ(json["w"], 512);
    EXPECT_EQ(json["h"], 256);
    EXPECT_NEAR(json["fl_x"].get<double>(), 256.0 / std::tan(0.5 * fov), 1e-3);
    EXPECT_EQ(json["fl_x"], json["fl_y"]);
    EXPECT_EQ(json["cx"], 256.0);
    EXPECT_EQ(json["cy"], 128.0);
}

TEST(TransformsJsonTest, NormalAndDepthImagesAreNamedPerFrame) {
    const std::vector<glm::mat4> views(2, glm::mat4(1.0f));
    const nlohmann::json plain = transformsJson(1.0f, 8, 8, views);
    EXPECT_FALSE(plain["frames"][0].contains("normal_file_path"));
    EXPECT_FALSE(plain.contains("depth_scale"));
    const nlohmann::json withNormals = transformsJson(1.0f, 8, 8, views, {.normals = true});
    EXPECT_EQ(withNormals["frames"][1]["normal_file_path"], "./001_normal");
    EXPECT_FALSE(withNormals["frames"][1].contains("depth_file_path"));
    const nlohmann::json withDepth = transformsJson(1.0f, 8, 8, views, {.depth = true}, 0.5);
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
