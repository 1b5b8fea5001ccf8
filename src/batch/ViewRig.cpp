#include "encore/batch/ViewRig.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "batch/ModelSeed.h"

namespace encore::batch {
namespace {

// The direction of view `view` from the origin, before any jitter.
glm::vec3 viewDirection(const ViewRigOptions& options,
                        std::uint32_t view,
                        std::mt19937_64& generator) {
    if (options.distribution == CameraDistribution::Orbit) {
        const double azimuth = 2.0 * M_PI * double(view) / double(options.views);
        const double elevation = double(options.elevationDegrees) * M_PI / 180.0;
        return glm::vec3(float(std::cos(elevation) * std::sin(azimuth)), float(std::sin(elevation)),
                         float(std::cos(elevation) * std::cos(azimuth)));
    }
    // Uniform on the sphere: the height is uniform in [-1, 1] (Archimedes' hat-box theorem), the
    // azimuth uniform around it; on the upper hemisphere the height is uniform in [0, 1].
    const double unit = unitInterval(generator);
    const double height =
        options.distribution == CameraDistribution::UpperHemisphere ? unit : 2.0 * unit - 1.0;
    const double azimuth = 2.0 * M_PI * unitInterval(generator);
    const double ring = std::sqrt(std::max(0.0, 1.0 - height * height));
    return glm::vec3(float(ring * std::sin(azimuth)), float(height),
                     float(ring * std::cos(azimuth)));
}

// `direction` moved by up to `degrees` in azimuth and elevation, the elevation kept within the
// poles.
glm::vec3 jittered(const glm::vec3& direction, float degrees, std::mt19937_64& generator) {
    const double range = double(degrees) * M_PI / 180.0;
    const double azimuth = std::atan2(double(direction.x), double(direction.z)) +
                           range * (2.0 * unitInterval(generator) - 1.0);
    const double elevation = std::clamp(std::asin(std::clamp(double(direction.y), -1.0, 1.0)) +
                                            range * (2.0 * unitInterval(generator) - 1.0),
                                        -0.5 * M_PI, 0.5 * M_PI);
    return glm::vec3(float(std::cos(elevation) * std::sin(azimuth)), float(std::sin(elevation)),
                     float(std::cos(elevation) * std::cos(azimuth)));
}

}  // namespace

glm::mat4 lookAtCameraToWorld(const glm::vec3& eye, const glm::vec3& target) {
    const glm::vec3 forward = glm::normalize(target - eye);
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (glm::length(glm::cross(forward, up)) < 1e-6f) {
        up = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 trueUp = glm::cross(right, forward);
    glm::mat4 cameraToWorld(1.0f);
    cameraToWorld[0] = glm::vec4(right, 0.0f);
    cameraToWorld[1] = glm::vec4(trueUp, 0.0f);
    cameraToWorld[2] = glm::vec4(-forward, 0.0f);  // OpenGL cameras look along -Z.
    cameraToWorld[3] = glm::vec4(eye, 1.0f);
    return cameraToWorld;
}

std::vector<ViewCamera> viewCameras(const ViewRigOptions& options, std::string_view modelName) {
    const std::uint64_t seed = modelSeed(options.seed, modelName);
    std::mt19937_64 directions = randomStream(seed, RandomStream::Directions);
    std::mt19937_64 jitter = randomStream(seed, RandomStream::Jitter);
    std::mt19937_64 distances = randomStream(seed, RandomStream::Distance);
    std::mt19937_64 fields = randomStream(seed, RandomStream::FieldOfView);
    std::vector<ViewCamera> views;
    for (std::uint32_t view = 0; view < options.views; ++view) {
        glm::vec3 direction = viewDirection(options, view, directions);
        if (options.jitterDegrees > 0.0f) {
            direction = jittered(direction, options.jitterDegrees, jitter);
        }
        const float distance = options.distance.at(unitInterval(distances));
        const float fovDegrees = options.horizontalFovDegrees.at(unitInterval(fields));
        views.push_back(
            {lookAtCameraToWorld(direction * distance, glm::vec3(0.0f)), glm::radians(fovDegrees)});
    }
    return views;
}

std::vector<glm::mat4> viewMatrices(const ViewRigOptions& options, std::string_view modelName) {
    std::vector<glm::mat4> matrices;
    for (const ViewCamera& view : viewCameras(options, modelName)) {
        matrices.push_back(view.cameraToWorld);
    }
    return matrices;
}

glm::mat4 normalization(const scene::Bounds& bounds, bool normalize) {
    if (!normalize || bounds.empty()) {
        return glm::mat4(1.0f);
    }
    const glm::vec3 extent = bounds.max - bounds.min;
    const float largest = std::max({extent.x, extent.y, extent.z});
    if (!(largest > std::numeric_limits<float>::min())) {
        return glm::translate(glm::mat4(1.0f), -bounds.center());
    }
    return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / largest)) *
           glm::translate(glm::mat4(1.0f), -bounds.center());
}

float verticalFov(float horizontalFovRadians, float aspect) {
    return 2.0f * std::atan(std::tan(0.5f * horizontalFovRadians) / aspect);
}

render::Camera renderCamera(const glm::mat4& cameraToWorld,
                            const glm::mat4& normalization,
                            float horizontalFovRadians,
                            float aspect) {
    // The normalisation is a uniform scale and a translation, so the camera keeps its
    // orientation and only its position and distances change: the view stays rigid.
    const float scale = normalization[0][0];
    const glm::mat4 toModel = glm::inverse(normalization);
    glm::mat4 modelCameraToWorld = cameraToWorld;
    modelCameraToWorld[3] = toModel * cameraToWorld[3];
    const float distance = glm::length(glm::vec3(cameraToWorld[3]));
    constexpr float kNearFraction = 0.01f;
    const float nearPlane = std::max(distance * kNearFraction, 1e-4f) / scale;

    // zfar 0: the infinite far plane.
    return render::Camera::perspective(
        modelCameraToWorld, verticalFov(horizontalFovRadians, aspect), aspect, nearPlane, 0.0f);
}

}  // namespace encore::batch
