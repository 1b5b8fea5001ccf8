#include "batch/TransformsJson.h"

#include <algorithm>
#include <cmath>

#include "batch/CameraConvention.h"
#include "batch/OptionNames.h"

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

// An orthographic view has no focal length: its span, and the image's size and centre.
void addOrthographic(nlohmann::json& json,
                     std::uint32_t width,
                     std::uint32_t height,
                     float orthoScale) {
    const PinholeIntrinsics centre = intrinsicsFor(width, height, 1.0f);
    json["projection"] = "orthographic";
    json["ortho_scale"] = double(orthoScale);
    json["cx"] = centre.centerX;
    json["cy"] = centre.centerY;
    json["w"] = width;
    json["h"] = height;
}

void addIntrinsics(nlohmann::json& json, const PinholeIntrinsics& intrinsics, float fovRadians) {
    json["camera_angle_x"] = double(fovRadians);
    json["fl_x"] = intrinsics.focalX;
    json["fl_y"] = intrinsics.focalY;
    json["cx"] = intrinsics.centerX;
    json["cy"] = intrinsics.centerY;
    json["w"] = std::uint32_t(intrinsics.width);
    json["h"] = std::uint32_t(intrinsics.height);
}

// Each pass's file, without extension as file_path has it: "normal_file_path": "./000_normal".
void addPassPaths(nlohmann::json& frame, std::size_t index, const ExtraImages& extras) {
    const std::pair<bool, ViewImage> passes[] = {{extras.normals, ViewImage::Normal},
                                                 {extras.depth, ViewImage::Depth},
                                                 {extras.albedo, ViewImage::Albedo},
                                                 {extras.material, ViewImage::Material},
                                                 {extras.segmentation, ViewImage::Segmentation},
                                                 {extras.hdr, ViewImage::Hdr},
                                                 {extras.coordinates, ViewImage::Coordinates}};
    for (const auto& [on, kind] : passes) {
        if (on) {
            const std::string stem = viewStem(index, kind);
            const std::string pass = stem.substr(stem.find('_') + 1);
            frame[pass + "_file_path"] = "./" + stem;
        }
    }
}

}  // namespace

void addPassConventions(nlohmann::json& json, const ExtraImages& extras) {
    // Only where one differs from the default, so that files written with the defaults are the
    // ones written before the options existed; metadata.json records every pass's conventions.
    if (extras.depth &&
        (extras.depthKind != DepthKind::Z || extras.depthUnit != DepthUnit::Normalized)) {
        json["depth_kind"] = std::string(nameOf(depthKindNames(), extras.depthKind));
        json["depth_unit"] = std::string(nameOf(depthUnitNames(), extras.depthUnit));
    }
    if (extras.normalsAsFloats()) {
        json["normal_space"] = std::string(nameOf(normalSpaceNames(), extras.normalSpace));
        json["normal_kind"] = std::string(nameOf(normalKindNames(), extras.normalKind));
        json["normal_format"] = std::string(nameOf(normalFormatNames(), extras.normalFormat));
    }
    if (extras.coordinates) {
        json["coordinates_format"] =
            std::string(nameOf(coordinatesFormatNames(), extras.coordinatesFormat));
    }
}

nlohmann::json transformsJson(std::span<const ViewCamera> views,
                              std::uint32_t width,
                              std::uint32_t height,
                              const ExtraImages& extras,
                              double depthScale,
                              const ModelLighting* lighting,
                              std::span<const SegmentationName> segmentation,
                              CameraConvention convention) {
    nlohmann::json json;
    json["camera_convention"] = std::string(nameOf(cameraConventionNames(), convention));
    const bool sharedFov = std::all_of(views.begin(), views.end(), [&](const ViewCamera& view) {
        return view.horizontalFovRadians == views.front().horizontalFovRadians &&
               view.projection == views.front().projection &&
               view.orthoScale == views.front().orthoScale;
    });
    if (!views.empty() && sharedFov && views.front().projection == Projection::Orthographic) {
        addOrthographic(json, width, height, views.front().orthoScale);
    } else if (!views.empty() && sharedFov) {
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
        nlohmann::json rows = nlohmann::json::array();
        if (convention == CameraConvention::OpenGl) {
            // The matrix as the renderer holds it, each float written exactly.
            const glm::mat4& cameraToWorld = views[index].cameraToWorld;
            for (int row = 0; row < 4; ++row) {
                nlohmann::json values = nlohmann::json::array();
                for (int column = 0; column < 4; ++column) {
                    values.push_back(double(cameraToWorld[column][row]));  // glm: [column][row]
                }
                rows.push_back(std::move(values));
            }
        } else {
            const glm::dmat4 cameraToWorld =
                cameraToWorldIn(views[index].cameraToWorld, convention);
            for (int row = 0; row < 4; ++row) {
                nlohmann::json values = nlohmann::json::array();
                for (int column = 0; column < 4; ++column) {
                    values.push_back(cameraToWorld[column][row]);
                }
                rows.push_back(std::move(values));
            }
        }
        nlohmann::json frame = {{"file_path", "./" + viewStem(index)},
                                {"transform_matrix", std::move(rows)}};
        if (views[index].projection == Projection::Orthographic) {
            addOrthographic(frame, width, height, views[index].orthoScale);
        } else {
            const float fov = views[index].horizontalFovRadians;
            addIntrinsics(frame, intrinsicsFor(width, height, fov), fov);
        }
        addPassPaths(frame, index, extras);
        if (lighting) {
            frame["environment"] = lighting->environment;
            frame["rotation"] = double(lighting->rotationDegrees);
            frame["intensity"] = double(lighting->intensity);
        }
        frames.push_back(std::move(frame));
    }
    if (extras.depth && extras.depthFormat == DepthFormat::Png) {
        json["depth_scale"] = depthScale;
    }
    if (extras.depth && extras.depthFormat == DepthFormat::Exr) {
        json["depth_format"] = "exr";
    }
    addPassConventions(json, extras);
    if (extras.segmentation) {
        json["segmentation_by"] = std::string(nameOf(segmentationByNames(), extras.segmentationBy));
        nlohmann::json ids = nlohmann::json::array();
        for (const SegmentationName& name : segmentation) {
            ids.push_back({{"id", name.id}, {"name", name.name}});
        }
        json["segmentation_ids"] = std::move(ids);
    }
    json["frames"] = std::move(frames);
    return json;
}

}  // namespace encore::batch
