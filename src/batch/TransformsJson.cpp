#include "batch/TransformsJson.h"

#include <cmath>

namespace encore::batch {

PinholeIntrinsics intrinsicsFor(std::uint32_t width,
                                std::uint32_t height,
                                float horizontalFovRadians) {
    PinholeIntrinsics intrinsics;
    intrinsics.width = width;
    intrinsics.height = height;
    intrinsics.focalX = 0.5 * double(width) / std::tan(0.5 * double(horizontalFovRadians));
    intrinsics.focalY = intrinsics.focalX;
    intrinsics.centerX = 0.5 * double(width);
    intrinsics.centerY = 0.5 * double(height);
    return intrinsics;
}

nlohmann::json transformsJson(float horizontalFovRadians,
                              std::uint32_t width,
                              std::uint32_t height,
                              std::span<const glm::mat4> cameraToWorld,
                              const ExtraImages& extras,
                              double depthScale) {
    const PinholeIntrinsics intrinsics = intrinsicsFor(width, height, horizontalFovRadians);
    nlohmann::json json;
    json["camera_angle_x"] = double(horizontalFovRadians);
    json["w"] = width;
    json["h"] = height;
    json["fl_x"] = intrinsics.focalX;
    json["fl_y"] = intrinsics.focalY;
    json["cx"] = intrinsics.centerX;
    json["cy"] = intrinsics.centerY;
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t index = 0; index < cameraToWorld.size(); ++index) {
        nlohmann::json rows = nlohmann::json::array();
        for (int row = 0; row < 4; ++row) {
            nlohmann::json values = nlohmann::json::array();
            for (int column = 0; column < 4; ++column) {
                values.push_back(double(cameraToWorld[index][column][row]));  // glm: [column][row]
            }
            rows.push_back(std::move(values));
        }
        nlohmann::json frame = {{"file_path", "./" + viewStem(index)},
                                {"transform_matrix", std::move(rows)}};
        if (extras.normals) {
            frame["normal_file_path"] = "./" + viewStem(index, ViewImage::Normal);
        }
        if (extras.depth) {
            frame["depth_file_path"] = "./" + viewStem(index, ViewImage::Depth);
        }
        frames.push_back(std::move(frame));
    }
    if (extras.depth) {
        json["depth_scale"] = depthScale;
    }
    json["frames"] = std::move(frames);
    return json;
}

}  // namespace encore::batch
