#include "CameraOptions.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace encore::app {

namespace {

// Parses a whole finite number; nullopt for anything else ("1x", "", "nan", "inf").
std::optional<float> parseNumber(const std::string& text) {
    if (text.empty()) {
        return std::nullopt;
    }
    char* end = nullptr;
    errno = 0;
    const float value = std::strtof(text.c_str(), &end);
    if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

std::optional<glm::vec3> parseVec3(const std::string& text) {
    glm::vec3 value(0.0f);
    std::size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = text.find(',', start);
        if ((i < 2) != (comma != std::string::npos)) {
            return std::nullopt;  // Fewer or more than three components.
        }
        const auto number = parseNumber(text.substr(start, comma - start));
        if (!number) {
            return std::nullopt;
        }
        value[i] = *number;
        start = comma + 1;
    }
    return value;
}

CLI::Validator vec3Validator() {
    return CLI::Validator(
        [](std::string& input) -> std::string {
            return parseVec3(input) ? "" : "expected three numbers X,Y,Z, got '" + input + "'";
        },
        "");  // The option's type name says X,Y,Z already.
}

// A finite number strictly between `low` and `high`.
CLI::Validator openRange(float low, float high, const std::string& description) {
    return CLI::Validator(
        [low, high, description](std::string& input) -> std::string {
            const auto value = parseNumber(input);
            if (!value || !(*value > low) || !(*value < high)) {
                return "expected a number " + description + ", got '" + input + "'";
            }
            return "";
        },
        description);
}

std::string fileOf(const scene::SceneData& scene) {
    return scene.sourcePath.string();
}

const char* projectionName(scene::CameraProjection projection) {
    return projection == scene::CameraProjection::Orthographic ? "orthographic" : "perspective";
}

// "0 'Front' (perspective), 1 (orthographic)" for error messages.
std::string cameraList(const scene::SceneData& scene) {
    std::string list;
    for (std::size_t i = 0; i < scene.cameraInstances.size(); ++i) {
        const scene::CameraId id = scene.cameraInstances[i].camera;
        list += list.empty() ? "" : ", ";
        list += std::to_string(i);
        if (id.index() < scene.cameras.size()) {
            const scene::CameraData& camera = scene.cameras[id.index()];
            list += camera.name.empty() ? "" : " '" + camera.name + "'";
            list += std::string(" (") + projectionName(camera.projection) + ")";
        }
    }
    return list;
}

bool isIndex(const std::string& text) {
    return !text.empty() && text.size() < 10 &&
           text.find_first_not_of("0123456789") == std::string::npos;
}

Result<const scene::CameraInstance*> findCamera(const std::string& wanted,
                                                const scene::SceneData& scene) {
    if (scene.cameraInstances.empty()) {
        return makeError(ErrorCode::InvalidArgument,
                         fileOf(scene) + ": --camera " + wanted +
                             ": the scene places no cameras (use --camera-position and --target, "
                             "or leave out --camera for the automatic framing).");
    }
    if (isIndex(wanted)) {
        const std::size_t index = std::stoul(wanted);
        if (index < scene.cameraInstances.size()) {
            return &scene.cameraInstances[index];
        }
    } else {
        for (const scene::CameraInstance& instance : scene.cameraInstances) {
            if (instance.camera.index() < scene.cameras.size() &&
                scene.cameras[instance.camera.index()].name == wanted) {
                return &instance;
            }
        }
    }
    return makeError(ErrorCode::InvalidArgument, fileOf(scene) + ": there is no camera '" + wanted +
                                                     "' (the cameras are: " + cameraList(scene) +
                                                     ").");
}

Result<void> checkClipDistances(const scene::SceneData& scene, float znear, float zfar) {
    // zfar <= 0 stands for an infinite far plane here, which is always beyond znear.
    if (zfar > 0.0f && !(zfar > znear)) {
        return makeError(ErrorCode::InvalidArgument, fileOf(scene) + ": the far plane (" +
                                                         std::to_string(zfar) +
                                                         ") must be farther than the near plane (" +
                                                         std::to_string(znear) + ").");
    }
    return {};
}

Result<render::Camera> gltfCamera(const CameraOptions& options,
                                  const scene::SceneData& scene,
                                  float aspect) {
    ENCORE_TRY_ASSIGN(auto instance, findCamera(options.camera, scene));
    const scene::CameraInstance& placed = *instance;
    if (placed.camera.index() >= scene.cameras.size()) {
        return makeError(ErrorCode::InvalidFormat, fileOf(scene) + ": camera instance '" +
                                                       options.camera +
                                                       "' refers to a missing camera (" +
                                                       std::to_string(placed.camera.value) + ").");
    }
    scene::CameraData camera = scene.cameras[placed.camera.index()];
    const bool orthographic = camera.projection == scene::CameraProjection::Orthographic;
    if (options.yfovDegrees) {
        if (orthographic) {
            return makeError(ErrorCode::InvalidArgument,
                             fileOf(scene) + ": --yfov does not apply to camera '" +
                                 options.camera + "', which is orthographic.");
        }
        camera.yfov = glm::radians(*options.yfovDegrees);
    }
    camera.znear = options.znear.value_or(camera.znear);
    camera.zfar = options.zfar.value_or(camera.zfar);
    ENCORE_TRY(checkClipDistances(scene, camera.znear, camera.zfar));
    if (orthographic && !(camera.zfar > camera.znear)) {
        return makeError(ErrorCode::InvalidArgument,
                         fileOf(scene) + ": orthographic camera '" + options.camera +
                             "' needs a far plane (--zfar) beyond its near plane.");
    }
    return render::Camera::fromGltf(camera, placed.world, aspect);
}

}  // namespace

void addCameraOptions(CLI::App& command, CameraOptions& options) {
    auto* camera = command.add_option("--camera", options.camera,
                                      "View through the scene's camera N (0-based, in node order) "
                                      "or the camera named NAME");
    camera->type_name("N|NAME");
    auto* position =
        command
            .add_option_function<std::string>(
                "--camera-position",
                [&options](const std::string& text) { options.position = parseVec3(text); },
                "Put the camera here (with --target; negative values: "
                "--camera-position=-1,2,3)")
            ->check(vec3Validator())
            ->type_name("X,Y,Z");
    auto* target =
        command
            .add_option_function<std::string>(
                "--target",
                [&options](const std::string& text) { options.target = parseVec3(text); },
                "Point the camera at this point (with --camera-position)")
            ->check(vec3Validator())
            ->type_name("X,Y,Z");
    position->needs(target)->excludes(camera);
    target->needs(position)->excludes(camera);
    camera->excludes(position)->excludes(target);
    command
        .add_option_function<float>(
            "--yfov", [&options](const float& degrees) { options.yfovDegrees = degrees; },
            "Vertical field of view in degrees (default 45, or the glTF camera's)")
        ->check(openRange(0.0f, 180.0f, "in (0, 180)"))
        ->type_name("DEGREES");
    command
        .add_option_function<float>(
            "--znear", [&options](const float& znear) { options.znear = znear; },
            "Near clipping distance (default 1/1000 of the distance to --target, or the glTF "
            "camera's, or the framing's)")
        ->check(openRange(0.0f, std::numeric_limits<float>::max(), "> 0"))
        ->type_name("DISTANCE");
    command
        .add_option_function<float>(
            "--zfar", [&options](const float& zfar) { options.zfar = zfar; },
            "Far clipping distance, beyond --znear (default: infinite with --target, the glTF "
            "camera's, or the framing's)")
        ->check(openRange(0.0f, std::numeric_limits<float>::max(), "> 0"))
        ->type_name("DISTANCE");
}

Result<render::Camera> resolveCamera(const CameraOptions& options,
                                     const scene::SceneData& scene,
                                     float aspect) {
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) {
        return makeError(
            ErrorCode::InvalidArgument,
            "The image's aspect ratio (" + std::to_string(aspect) + ") must be a positive number.");
    }
    if (!options.camera.empty()) {
        return gltfCamera(options, scene, aspect);
    }
    const float yfov = glm::radians(options.yfovDegrees.value_or(kDefaultYfovDegrees));
    if (options.position || options.target) {
        if (!options.position || !options.target) {
            return makeError(ErrorCode::InvalidArgument,
                             "--camera-position and --target go together.");
        }
        const float distance = glm::length(*options.target - *options.position);
        if (!(distance > 0.0f) || !std::isfinite(distance)) {
            return makeError(ErrorCode::InvalidArgument,
                             fileOf(scene) + ": --camera-position and --target must differ.");
        }
        const float znear = options.znear.value_or(distance * kDefaultNearFraction);
        const float zfar = options.zfar.value_or(0.0f);  // 0: infinite.
        ENCORE_TRY(checkClipDistances(scene, znear, zfar));
        return render::Camera::lookAt(*options.position, *options.target, yfov, aspect, znear,
                                      zfar);
    }
    render::Camera camera =
        render::Camera::framing(scene.bounds, aspect, glm::radians(options.yawDegrees), yfov);
    if (options.znear || options.zfar) {
        const float znear = options.znear.value_or(camera.nearPlane);
        const float zfar = options.zfar.value_or(camera.farPlane);
        ENCORE_TRY(checkClipDistances(scene, znear, zfar));
        camera.projection = render::perspectiveProjection(yfov, aspect, znear, zfar);
        camera.nearPlane = znear;
        camera.farPlane = zfar;
    }
    return camera;
}

}  // namespace encore::app
