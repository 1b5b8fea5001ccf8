// Issue 50's camera placements: fixed azimuth, elevation and distance lists, the Hammersley and
// Fibonacci distributions, MVDream's distance relative to the field of view, orthographic views.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "batch/BatchOptionTable.h"
#include "batch/BatchOptionsValidation.h"
#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

constexpr float kEpsilon = 1e-5f;

glm::vec3 position(const ViewCamera& view) {
    return glm::vec3(view.cameraToWorld[3]);
}

// Azimuth from +Z towards +X and elevation above the horizon, in degrees.
float azimuthOf(const glm::vec3& eye) {
    return glm::degrees(std::atan2(eye.x, eye.z));
}
float elevationOf(const glm::vec3& eye) {
    return glm::degrees(std::asin(eye.y / glm::length(eye)));
}

TEST(CameraListsTest, ListedViewsLookFromTheDegreesGiven) {
    ViewRigOptions options;
    options.azimuthsDegrees = {0.0f, 45.0f, 90.0f, 180.0f, -90.0f, -45.0f};
    options.elevationsDegrees = {0.0f, 10.0f, 20.0f, -10.0f, 30.0f, -30.0f};
    options.distances = {1.0f, 1.5f, 2.0f, 2.5f, 3.0f, 3.5f};
    options.views = 12;  // Replaced by the lists' length.
    const std::vector<ViewCamera> views = viewCameras(options, "model");
    ASSERT_EQ(views.size(), 6u);
    ASSERT_EQ(viewCount(options), 6u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const glm::vec3 eye = position(views[i]);
        const float azimuth = azimuthOf(eye);
        EXPECT_NEAR(std::remainder(azimuth - options.azimuthsDegrees[i], 360.0f), 0.0f, 1e-3f) << i;
        EXPECT_NEAR(elevationOf(eye), options.elevationsDegrees[i], 1e-3f) << i;
        EXPECT_NEAR(glm::length(eye), options.distances[i], kEpsilon) << i;
        // Each looks at the origin.
        EXPECT_NEAR(glm::dot(-glm::vec3(views[i].cameraToWorld[2]), glm::normalize(-eye)), 1.0f,
                    kEpsilon);
    }
    // Azimuth 90 is the model's +X side, 0 its front (+Z).
    EXPECT_GT(position(views[2]).x, 1.8f);
    EXPECT_GT(position(views[0]).z, 0.9f);
}

TEST(CameraListsTest, AListOfOneAppliesToEveryView) {
    ViewRigOptions options;
    options.azimuthsDegrees = {10.0f, 20.0f, 30.0f};
    options.elevationsDegrees = {15.0f};
    const std::vector<ViewCamera> views = viewCameras(options);
    ASSERT_EQ(views.size(), 3u);
    for (const ViewCamera& view : views) {
        EXPECT_NEAR(elevationOf(position(view)), 15.0f, 1e-3f);
        EXPECT_NEAR(glm::length(position(view)), 1.5f, kEpsilon);
    }
    // Elevations alone are spread evenly in azimuth over --views.
    ViewRigOptions spread;
    spread.views = 4;
    spread.elevationsDegrees = {-20.0f};
    const std::vector<ViewCamera> around = viewCameras(spread);
    ASSERT_EQ(around.size(), 4u);
    for (std::size_t i = 0; i < around.size(); ++i) {
        EXPECT_NEAR(std::remainder(azimuthOf(position(around[i])) - 90.0f * float(i), 360.0f), 0.0f,
                    1e-3f);
        EXPECT_NEAR(elevationOf(position(around[i])), -20.0f, 1e-3f);
    }
    // The poles: looking straight down stays a rigid camera.
    ViewRigOptions top;
    top.azimuthsDegrees = {0.0f};
    top.elevationsDegrees = {90.0f};
    top.views = 1;
    const ViewCamera pole = viewCameras(top).front();
    EXPECT_NEAR(elevationOf(position(pole)), 90.0f, 1e-3f);
    EXPECT_NEAR(glm::determinant(glm::mat3(pole.cameraToWorld)), 1.0f, kEpsilon);
}

TEST(CameraListsTest, ListsOfDifferentLengthsAreRefused) {
    BatchOptions options;
    options.views.azimuthsDegrees = {0.0f, 90.0f, 180.0f};
    options.views.elevationsDegrees = {0.0f, 10.0f};
    auto valid = validateBatchOptions(options);
    ASSERT_FALSE(valid.ok());
    EXPECT_NE(valid.error().message.find("differ in length (3 and 2)"), std::string::npos)
        << valid.error().message;
    options.views.elevationsDegrees = {95.0f};
    valid = validateBatchOptions(options);
    ASSERT_FALSE(valid.ok());
    EXPECT_NE(valid.error().message.find("elevations must lie in [-90, 90] (not 95)"),
              std::string::npos)
        << valid.error().message;
}

TEST(CameraListsTest, BadListTextNamesTheOptionAndTheItem) {
    BatchOptions options;
    const GivenOption given[] = {
        {findBatchOption("azimuths", OptionFront::CommandLine), "0,ninety,180"}};
    auto applied = applyBatchOptions(options, given, OptionFront::CommandLine);
    ASSERT_FALSE(applied.ok());
    EXPECT_EQ(applied.error().message,
              "--azimuths takes numbers separated by commas, A,B,... ('ninety' is not a number) "
              "(not '0,ninety,180').");
    const GivenOption empty[] = {{findBatchOption("elevations", OptionFront::Python), "0,,1"}};
    applied = applyBatchOptions(options, empty, OptionFront::Python);
    ASSERT_FALSE(applied.ok());
    EXPECT_EQ(applied.error().message.substr(0, 16), "elevations takes");
}

// TRELLIS's sphere_hammersley_sequence: view i's height 2 (i + u) / n - 1 lies in its own
// stratum, its azimuth follows the base-2 radical inverse; the offsets differ per model.
TEST(CameraListsTest, HammersleyViewsFillTheirStrata) {
    ViewRigOptions options;
    options.distribution = CameraDistribution::Hammersley;
    options.views = 150;
    options.distance = 2.0f;
    const std::vector<ViewCamera> views = viewCameras(options, "a");
    ASSERT_EQ(views.size(), 150u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const glm::vec3 direction = glm::normalize(position(views[i]));
        EXPECT_GE(direction.y, 2.0f * float(i) / 150.0f - 1.0f - kEpsilon) << i;
        EXPECT_LE(direction.y, 2.0f * float(i + 1) / 150.0f - 1.0f + kEpsilon) << i;
        EXPECT_NEAR(glm::length(position(views[i])), 2.0f, kEpsilon);
    }
    // Views 0 and 1 are half a turn apart in azimuth (radical inverses 0 and 0.5).
    const float turn = azimuthOf(position(views[1])) - azimuthOf(position(views[0]));
    EXPECT_NEAR(std::abs(std::remainder(turn, 360.0f)), 180.0f, 1e-2f);
    EXPECT_NE(viewCameras(options, "b"), views);  // Another model, other offsets.
    EXPECT_EQ(viewCameras(options, "a"), views);  // The same one, the same views.
}

TEST(CameraListsTest, FibonacciViewsSpiralEvenly) {
    ViewRigOptions options;
    options.distribution = CameraDistribution::Fibonacci;
    options.views = 20;
    const std::vector<ViewCamera> views = viewCameras(options, "a");
    ASSERT_EQ(views.size(), 20u);
    const float golden = 180.0f * (3.0f - std::sqrt(5.0f));
    for (std::size_t i = 0; i < views.size(); ++i) {
        const glm::vec3 direction = glm::normalize(position(views[i]));
        EXPECT_NEAR(direction.y, 1.0f - (2.0f * float(i) + 1.0f) / 20.0f, kEpsilon);
        if (i > 0) {
            const float step = azimuthOf(position(views[i])) - azimuthOf(position(views[i - 1]));
            EXPECT_NEAR(std::remainder(step - golden, 360.0f), 0.0f, 1e-2f) << i;
        }
    }
    EXPECT_EQ(viewCameras(options, "b"), views);  // Nothing drawn.
}

TEST(CameraListsTest, ElevationRangesAreDrawnPerView) {
    ViewRigOptions options;
    options.views = 32;
    options.elevationDegrees = ValueRange(0.0f, 30.0f);
    std::set<float> elevations;
    for (const ViewCamera& view : viewCameras(options, "m")) {
        const float elevation = elevationOf(position(view));
        EXPECT_GE(elevation, -1e-3f);
        EXPECT_LE(elevation, 30.0f + 1e-3f);
        elevations.insert(elevation);
    }
    EXPECT_GT(elevations.size(), 20u);
}

// MVDream (threestudio's relative_radius): the camera stands at distance / tan(fov / 2).
TEST(CameraListsTest, DistanceRelativeToTheFieldOfView) {
    ViewRigOptions options;
    options.views = 8;
    options.distance = 1.0f;
    options.horizontalFovDegrees = ValueRange(15.0f, 60.0f);
    options.distanceRelativeToFov = true;
    for (const ViewCamera& view : viewCameras(options, "m")) {
        EXPECT_NEAR(glm::length(position(view)) * std::tan(0.5f * view.horizontalFovRadians), 1.0f,
                    1e-4f);
    }
    EXPECT_NEAR(farthestDistance(options), 1.0f / std::tan(glm::radians(7.5f)), 1e-3f);
}

TEST(CameraListsTest, OrthographicViewsSpanTheirScale) {
    ViewRigOptions options;
    options.projection = Projection::Orthographic;
    options.orthoScale = 1.35f;
    options.views = 2;
    const std::vector<ViewCamera> views = viewCameras(options);
    ASSERT_EQ(views.size(), 2u);
    EXPECT_EQ(views[0].projection, Projection::Orthographic);
    EXPECT_EQ(views[0].orthoScale, 1.35f);
    // The span is across the larger side: a wide image is 1.35 wide, less high.
    EXPECT_EQ(orthographicHalfExtent(1.35f, 2.0f), glm::vec2(0.675f, 0.3375f));
    EXPECT_EQ(orthographicHalfExtent(1.35f, 0.5f), glm::vec2(0.3375f, 0.675f));
    // The render camera projects the unit box's corner at (0.5, 0.5) half way to the edge
    // (scale 2 for a model twice the unit box: normalisation scale 0.5).
    const glm::mat4 normalization = glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    ViewCamera front;
    front.cameraToWorld = lookAtCameraToWorld({0.0f, 0.0f, 2.0f}, glm::vec3(0.0f));
    front.projection = Projection::Orthographic;
    front.orthoScale = 2.0f;
    const render::Camera camera = renderCamera(front, normalization, 1.0f);
    EXPECT_EQ(camera.kind, render::ProjectionKind::Orthographic);
    const glm::vec4 clip = camera.viewProjection() * glm::vec4(1.0f, 1.0f, 0.0f, 1.0f);
    EXPECT_NEAR(clip.x / clip.w, 0.5f, kEpsilon);
    EXPECT_NEAR(clip.y / clip.w, 0.5f, kEpsilon);
    EXPECT_GT(clip.z / clip.w, 0.0f);
    EXPECT_LT(clip.z / clip.w, 1.0f);
}

}  // namespace
}  // namespace encore::batch
