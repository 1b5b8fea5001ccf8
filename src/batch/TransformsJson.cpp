#include "batch/TransformsJson.h"

#include <algorithm>
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

namespace {

void addIntrinsics(nlohmann::json& json, const PinholeIntrinsics& intrinsics, float fovRadians) {
    json["camera_angle_x"] = double(fovRadians);
    json["fl_x"] = intrinsics.focalX;
    json["fl_y"] = intrinsics.focalY;
    json["cx"] = intrinsics.centerX;
    json["cy"] = intrinsics.centerY;
    json["w"] = std::uint32_t(intrinsics.width);
    json["h"] = std::uint32_t(intrinsics.height);
}

}  // namespace

nlohmann::json transformsJson(std::span<const ViewCamera> views,
                              std::uint32_t width,
                              std::uint32_t height,
                              const ExtraImages& extras,
                              double depthScale,
                              const ModelLighting* lighting) {
    nlohmann::json json;
    const bool sharedFov = std::all_of(views.begin(), views.end(), [&](const ViewCamera& view) {
        return view.horizontalFovRadians == views.front().horizontalFovRadians;
    });
    if (!views.empty() && sharedFov) {
        const float fov = views.front().horizontalFovRadians;
        addIntrinsics(json, intrinsicsFor(width, height, fov), fov);
    } else {
        // The principal point and the size are still shared.
        const PinholeIntrinsics centre = intrinsicsFor(width, height, 1.0f);
        json["w"] = width;
        json["h"] = height;
        json["cx"] = centre.centerX;
        json["cy"] = centre.centerY;
    }
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t index = 0; index < views.size(); ++index) {
        const glm::mat4& cameraToWorld = views[index].cameraToWorld;
        nlohmann::json rows = nlohmann::json::array();
        for (int row = 0; row < 4; ++row) {
            nlohmann::json values = nlohmann::json::array();
            for (int column = 0; column < 4; ++column) {
                values.push_back(double(cameraToWorld[column][row]));  // glm: [column][row]
            }
            rows.push_back(std::move(values));
        }
        nlohmann::json frame = {{"file_path", "./" + viewStem(index)},
                                {"transform_matrix", std::move(rows)}};
        const float fov = views[index].horizontalFovRadians;
        addIntrinsics(frame, intrinsicsFor(width, height, fov), fov);
        if (extras.normals) {
            frame["normal_file_path"] = "./" + viewStem(index, ViewImage::Normal);
        }
        if (extras.depth) {
            frame["depth_file_path"] = "./" + viewStem(index, ViewImage::Depth);
        }
        if (lighting) {
            frame["environment"] = lighting->environment;
            frame["rotation"] = double(lighting->rotationDegrees);
            frame["intensity"] = double(lighting->intensity);
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
