#include "encore/batch/ViewRig.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "batch/ModelSeed.h"

namespace encore::batch {
namespace {

constexpr double kDegrees = M_PI / 180.0;

// The direction at `azimuth` and `elevation` (radians; the header's convention).
glm::vec3 directionAt(double azimuth, double elevation) {
    return glm::vec3(float(std::cos(elevation) * std::sin(azimuth)), float(std::sin(elevation)),
                     float(std::cos(elevation) * std::cos(azimuth)));
}

// The direction at `height` (the sine of the elevation) and `azimuth` (radians).
glm::vec3 directionAtHeight(double height, double azimuth) {
    const double ring = std::sqrt(std::max(0.0, 1.0 - height * height));
    return glm::vec3(float(ring * std::sin(azimuth)), float(height),
                     float(ring * std::cos(azimuth)));
}

// Van der Corput's radical inverse in base 2: the bits of `index` mirrored about the point.
double radicalInverse2(std::uint32_t index) {
    double value = 0.0;
    double digit = 0.5;
    for (; index > 0; index >>= 1, digit *= 0.5) {
        value += (index & 1u) * digit;
    }
    return value;
}

// Element `view` of a list that holds one value per view or one for all.
float listed(const std::vector<float>& values, std::uint32_t view) {
    return values[values.size() == 1 ? 0 : view];
}

// Where the draws of a rig go that are made once per model.
struct ModelDraws {
    double hammersleyU = 0.0;
    double hammersleyV = 0.0;
};

// The direction of view `view` from the origin, before any jitter.
glm::vec3 viewDirection(const ViewRigOptions& options,
                        std::uint32_t view,
                        std::uint32_t views,
                        const ModelDraws& draws,
                        std::mt19937_64& generator,
                        std::mt19937_64& elevations) {
    const bool listedAzimuths = !options.azimuthsDegrees.empty();
    if (listedAzimuths || !options.elevationsDegrees.empty()) {
        const double azimuth = listedAzimuths ? listed(options.azimuthsDegrees, view) * kDegrees
                                              : 2.0 * M_PI * double(view) / double(views);
        const double elevation =
            options.elevationsDegrees.empty()
                ? options.elevationDegrees.at(unitInterval(elevations)) * kDegrees
                : listed(options.elevationsDegrees, view) * kDegrees;
        return directionAt(azimuth, elevation);
    }
    switch (options.distribution) {
        case CameraDistribution::Orbit:
            return directionAt(2.0 * M_PI * double(view) / double(views),
                               options.elevationDegrees.at(unitInterval(elevations)) * kDegrees);
        case CameraDistribution::Hammersley: {
            // TRELLIS: u = i / n + offset_u / n, v = radicalInverse2(i) + offset_v; the pitch is
            // acos(1 - 2u) - pi / 2, whose sine is 2u - 1; the yaw 2 pi v from Blender's +X.
            const double u = (double(view) + draws.hammersleyU) / double(views);
            const double v = radicalInverse2(view) + draws.hammersleyV;
            return directionAtHeight(std::clamp(2.0 * u - 1.0, -1.0, 1.0),
                                     2.0 * M_PI * v + 0.5 * M_PI);
        }
        case CameraDistribution::Fibonacci: {
            const double goldenAngle = M_PI * (3.0 - std::sqrt(5.0));
            return directionAtHeight(1.0 - (2.0 * double(view) + 1.0) / double(views),
                                     goldenAngle * double(view));
        }
        case CameraDistribution::Sphere:
        case CameraDistribution::UpperHemisphere:
            break;
    }
    // Uniform on the sphere: the height is uniform in [-1, 1] (Archimedes' hat-box theorem), the
    // azimuth uniform around it; on the upper hemisphere the height is uniform in [0, 1].
    const double unit = unitInterval(generator);
    const double height =
        options.distribution == CameraDistribution::UpperHemisphere ? unit : 2.0 * unit - 1.0;
    const double azimuth = 2.0 * M_PI * unitInterval(generator);
    return directionAtHeight(height, azimuth);
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
    return directionAt(azimuth, elevation);
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

std::uint32_t viewCount(const ViewRigOptions& options) {
    if (!options.poses.empty()) {
        return std::uint32_t(options.poses.size());
    }
    // The longest list, when one holds several values; else `views`.
    const std::size_t listed =
        std::max({options.azimuthsDegrees.size(), options.elevationsDegrees.size(),
                  options.distances.size()});
    return listed > 1 ? std::uint32_t(listed) : options.views;
}

float farthestDistance(const ViewRigOptions& options) {
    if (!options.poses.empty()) {
        float farthest = 0.0f;
        for (const ViewCamera& pose : options.poses) {
            farthest = std::max(farthest, glm::length(glm::vec3(pose.cameraToWorld[3])));
        }
        return farthest > 0.0f ? farthest : 1.0f;
    }
    float farthest = options.distances.empty()
                         ? options.distance.max
                         : *std::max_element(options.distances.begin(), options.distances.end());
    if (options.distanceRelativeToFov && options.projection == Projection::Perspective) {
        // The narrowest field of view puts the camera farthest (a square image's vertical field
        // of view is its horizontal one; a wider image's is narrower, which this bound ignores).
        farthest /= std::tan(0.5f * glm::radians(options.horizontalFovDegrees.min));
    }
    return farthest;
}

std::vector<ViewCamera> viewCameras(const ViewRigOptions& options, std::string_view modelName) {
    if (!options.poses.empty()) {
        return options.poses;
    }
    const std::uint64_t seed = modelSeed(options.seed, modelName);
    std::mt19937_64 directions = randomStream(seed, RandomStream::Directions);
    std::mt19937_64 jitter = randomStream(seed, RandomStream::Jitter);
    std::mt19937_64 distances = randomStream(seed, RandomStream::Distance);
    std::mt19937_64 fields = randomStream(seed, RandomStream::FieldOfView);
    std::mt19937_64 elevations = randomStream(seed, RandomStream::Elevation);
    ModelDraws draws;
    if (options.distribution == CameraDistribution::Hammersley) {
        draws.hammersleyU = unitInterval(directions);
        draws.hammersleyV = unitInterval(directions);
    }
    const std::uint32_t views = viewCount(options);
    std::vector<ViewCamera> cameras;
    for (std::uint32_t view = 0; view < views; ++view) {
        glm::vec3 direction = viewDirection(options, view, views, draws, directions, elevations);
        if (options.jitterDegrees > 0.0f) {
            direction = jittered(direction, options.jitterDegrees, jitter);
        }
        const double unitDistance = unitInterval(distances);
        float distance = options.distances.empty() ? options.distance.at(unitDistance)
                                                   : listed(options.distances, view);
        const float fovDegrees = options.horizontalFovDegrees.at(unitInterval(fields));
        ViewCamera camera;
        camera.horizontalFovRadians = glm::radians(fovDegrees);
        camera.projection = options.projection;
        if (options.projection == Projection::Orthographic) {
            camera.horizontalFovRadians = 0.0f;
            camera.orthoScale = options.orthoScale;
        } else if (options.distanceRelativeToFov) {
            distance /= std::tan(0.5f * camera.horizontalFovRadians);
        }
        camera.cameraToWorld = lookAtCameraToWorld(direction * distance, glm::vec3(0.0f));
        cameras.push_back(camera);
    }
    return cameras;
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

glm::vec2 orthographicHalfExtent(float orthoScale, float aspect) {
    // Blender's ortho_scale spans the larger side.
    return aspect >= 1.0f ? glm::vec2(0.5f * orthoScale, 0.5f * orthoScale / aspect)
                          : glm::vec2(0.5f * orthoScale * aspect, 0.5f * orthoScale);
}

render::Camera renderCamera(const ViewCamera& view, const glm::mat4& normalization, float aspect) {
    if (view.projection == Projection::Perspective) {
        return renderCamera(view.cameraToWorld, normalization, view.horizontalFovRadians, aspect);
    }
    const float scale = normalization[0][0];
    glm::mat4 modelCameraToWorld = view.cameraToWorld;
    modelCameraToWorld[3] = glm::inverse(normalization) * view.cameraToWorld[3];
    const float distance = std::max(glm::length(glm::vec3(view.cameraToWorld[3])), 1e-4f);
    // Depth is linear in an orthographic projection: a range of 10,000 near planes keeps its
    // steps far below a normalised model's details.
    constexpr float kNearFraction = 0.01f;
    constexpr float kFarMultiple = 100.0f;
    const glm::vec2 half = orthographicHalfExtent(view.orthoScale, aspect) / scale;
    return render::Camera::orthographic(modelCameraToWorld, half.x, half.y,
                                        distance * kNearFraction / scale,
                                        distance * kFarMultiple / scale);
}

}  // namespace encore::batch
