#include "encore/batch/ViewRig.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

namespace encore::batch {
namespace {

// A double in [0, 1) from the generator's raw bits: std::uniform_real_distribution may differ
// between standard libraries, and --seed promises the same views everywhere.
double unitInterval(std::mt19937_64& generator) {
    return double(generator() >> 11) * 0x1.0p-53;
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

std::vector<glm::mat4> viewMatrices(const ViewRigOptions& options) {
    std::vector<glm::mat4> views;
    std::mt19937_64 generator(options.seed);
    for (std::uint32_t view = 0; view < options.views; ++view) {
        glm::vec3 direction;
        if (options.random) {
            // Uniform on the sphere: the height is uniform in [-1, 1] (Archimedes' hat-box
            // theorem), the azimuth uniform around it.
            const double height = 2.0 * unitInterval(generator) - 1.0;
            const double azimuth = 2.0 * M_PI * unitInterval(generator);
            const double ring = std::sqrt(std::max(0.0, 1.0 - height * height));
            direction = glm::vec3(float(ring * std::sin(azimuth)), float(height),
                                  float(ring * std::cos(azimuth)));
        } else {
            const double azimuth = 2.0 * M_PI * double(view) / double(options.views);
            const double elevation = double(options.elevationDegrees) * M_PI / 180.0;
            direction = glm::vec3(float(std::cos(elevation) * std::sin(azimuth)),
                                  float(std::sin(elevation)),
                                  float(std::cos(elevation) * std::cos(azimuth)));
        }
        views.push_back(lookAtCameraToWorld(direction * options.distance, glm::vec3(0.0f)));
    }
    return views;
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
