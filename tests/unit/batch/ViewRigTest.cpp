#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "encore/batch/ViewRig.h"

namespace encore::batch {
namespace {

constexpr float kEpsilon = 1e-5f;

glm::vec3 position(const glm::mat4& cameraToWorld) {
    return glm::vec3(cameraToWorld[3]);
}
glm::vec3 forward(const glm::mat4& cameraToWorld) {
    return -glm::vec3(cameraToWorld[2]);  // OpenGL cameras look along -Z.
}

// Rotation part orthonormal and right-handed.
void expectRigid(const glm::mat4& m) {
    const glm::mat3 rotation(m);
    const glm::mat3 product = glm::transpose(rotation) * rotation;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            EXPECT_NEAR(product[i][j], i == j ? 1.0f : 0.0f, kEpsilon);
        }
    }
    EXPECT_NEAR(glm::determinant(rotation), 1.0f, kEpsilon);
    EXPECT_EQ(m[0][3], 0.0f);
    EXPECT_EQ(m[3][3], 1.0f);
}

TEST(ViewRigTest, OrbitViewZeroLooksAtTheOriginFromTheFrontAbove) {
    ViewRigOptions options;
    const auto views = viewMatrices(options);
    ASSERT_EQ(views.size(), 12u);
    const glm::vec3 eye = position(views[0]);
    EXPECT_NEAR(eye.x, 0.0f, kEpsilon);
    EXPECT_GT(eye.z, 0.0f);
    EXPECT_NEAR(glm::length(eye), 1.5f, kEpsilon);
    EXPECT_NEAR(std::asin(eye.y / glm::length(eye)), glm::radians(30.0f), kEpsilon);
    const glm::vec3 toOrigin = glm::normalize(-eye);
    EXPECT_NEAR(glm::dot(forward(views[0]), toOrigin), 1.0f, kEpsilon);
    // Upright: the camera's +Y leans towards world +Y and its +X is horizontal.
    EXPECT_GT(views[0][1].y, 0.0f);
    EXPECT_NEAR(views[0][0].y, 0.0f, kEpsilon);
}

TEST(ViewRigTest, OrbitViewsAreEvenlySpacedAtTheElevation) {
    ViewRigOptions options;
    options.views = 8;
    options.elevationDegrees = -20.0f;
    options.distance = 3.0f;
    const auto views = viewMatrices(options);
    ASSERT_EQ(views.size(), 8u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        expectRigid(views[i]);
        const glm::vec3 eye = position(views[i]);
        EXPECT_NEAR(glm::length(eye), 3.0f, 1e-4f);
        EXPECT_NEAR(std::asin(eye.y / 3.0f), glm::radians(-20.0f), 1e-4f);
        EXPECT_NEAR(glm::dot(forward(views[i]), glm::normalize(-eye)), 1.0f, kEpsilon);
        const float azimuth = std::atan2(eye.x, eye.z);
        const float expected = glm::radians(45.0f * float(i));
        EXPECT_NEAR(std::remainder(azimuth - expected, 2.0f * float(M_PI)), 0.0f, 1e-4f) << i;
    }
}

TEST(ViewRigTest, StraightDownIsStillWellDefined) {
    const glm::mat4 m = lookAtCameraToWorld({0.0f, 2.0f, 0.0f}, glm::vec3(0.0f));
    expectRigid(m);
    EXPECT_NEAR(glm::dot(forward(m), {0.0f, -1.0f, 0.0f}), 1.0f, kEpsilon);
}

TEST(ViewRigTest, RandomViewsLieOnTheSphereAndRepeatWithTheSeed) {
    ViewRigOptions options;
    options.distribution = CameraDistribution::Sphere;
    options.views = 2000;
    options.seed = 7;
    options.distance = 2.0f;
    const auto views = viewMatrices(options);
    ASSERT_EQ(views.size(), 2000u);
    glm::dvec3 mean(0.0);
    double meanHeightSquared = 0.0;
    for (const glm::mat4& view : views) {
        expectRigid(view);
        const glm::vec3 eye = position(view);
        EXPECT_NEAR(glm::length(eye), 2.0f, 1e-4f);
        EXPECT_NEAR(glm::dot(forward(view), glm::normalize(-eye)), 1.0f, 1e-4f);
        mean += glm::dvec3(eye / 2.0f);
        meanHeightSquared += double(eye.y / 2.0f) * double(eye.y / 2.0f);
    }
    mean /= double(views.size());
    meanHeightSquared /= double(views.size());
    // Uniform on the sphere: the mean direction is 0 and E[y^2] = 1/3 (about 5 standard errors
    // of 2000 samples).
    EXPECT_LT(glm::length(mean), 0.07);
    EXPECT_NEAR(meanHeightSquared, 1.0 / 3.0, 0.03);

    EXPECT_EQ(viewMatrices(options), views);
    options.seed = 8;
    EXPECT_NE(viewMatrices(options), views);
}

TEST(ViewRigTest, UpperHemisphereViewsStayAboveTheHorizon) {
    ViewRigOptions options;
    options.distribution = CameraDistribution::UpperHemisphere;
    options.views = 2000;
    double meanHeight = 0.0;
    for (const glm::mat4& view : viewMatrices(options, "model")) {
        const glm::vec3 eye = position(view) / 1.5f;
        EXPECT_GE(eye.y, 0.0f);
        meanHeight += eye.y;
    }
    // Uniform on the hemisphere: the height is uniform in [0, 1].
    EXPECT_NEAR(meanHeight / 2000.0, 0.5, 0.03);
}

// Each model draws views of its own from the seed and its name, whatever else is asked for:
// the same name and seed give the same views, another name or seed others.
TEST(ViewRigTest, RandomViewsDependOnTheSeedAndTheModelName) {
    ViewRigOptions options;
    options.distribution = CameraDistribution::Sphere;
    options.views = 4;
    options.seed = 3;
    const auto a = viewCameras(options, "cars/a");
    EXPECT_EQ(viewCameras(options, "cars/a"), a);
    EXPECT_NE(viewCameras(options, "cars/b"), a);
    // No name: the seed alone, as Renderer.render_views draws them.
    EXPECT_NE(viewCameras(options, ""), a);
    options.seed = 4;
    EXPECT_NE(viewCameras(options, "cars/a"), a);
    // Ranges draw from streams of their own: the directions stay.
    options.seed = 3;
    options.distance = ValueRange(1.5f, 2.2f);
    options.horizontalFovDegrees = ValueRange(30.0f, 60.0f);
    const auto ranged = viewCameras(options, "cars/a");
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(glm::dot(forward(ranged[i].cameraToWorld), forward(a[i].cameraToWorld)), 1.0f,
                    1e-6f);
    }
}

TEST(ViewRigTest, DistanceAndFieldOfViewRangesAreDrawnPerView) {
    ViewRigOptions options;
    options.views = 500;
    options.distance = ValueRange(1.5f, 2.2f);
    options.horizontalFovDegrees = ValueRange(30.0f, 60.0f);
    const auto views = viewCameras(options, "m");
    float nearest = 10.0f, farthest = 0.0f, narrowest = 10.0f, widest = 0.0f;
    for (const ViewCamera& view : views) {
        expectRigid(view.cameraToWorld);
        const float distance = glm::length(position(view.cameraToWorld));
        nearest = std::min(nearest, distance);
        farthest = std::max(farthest, distance);
        narrowest = std::min(narrowest, view.horizontalFovRadians);
        widest = std::max(widest, view.horizontalFovRadians);
        // Still on the orbit, looking at the origin.
        EXPECT_NEAR(std::asin(position(view.cameraToWorld).y / distance), glm::radians(30.0f),
                    1e-4f);
    }
    EXPECT_GE(nearest, 1.5f - 1e-5f);
    EXPECT_LE(farthest, 2.2f + 1e-5f);
    EXPECT_LT(nearest, 1.55f);
    EXPECT_GT(farthest, 2.15f);
    EXPECT_GE(narrowest, glm::radians(30.0f) - 1e-6f);
    EXPECT_LE(widest, glm::radians(60.0f) + 1e-6f);
    EXPECT_GT(widest - narrowest, glm::radians(25.0f));
    // Fixed values are exactly the value.
    options.distance = 2.0f;
    options.horizontalFovDegrees = 40.0f;
    for (const ViewCamera& view : viewCameras(options, "m")) {
        EXPECT_NEAR(glm::length(position(view.cameraToWorld)), 2.0f, 1e-5f);
        EXPECT_EQ(view.horizontalFovRadians, glm::radians(40.0f));
    }
}

TEST(ViewRigTest, JitterMovesOrbitViewsByAtMostItsAngle) {
    ViewRigOptions options;
    const auto orbit = viewMatrices(options, "m");
    options.jitterDegrees = 10.0f;
    const auto jittered = viewMatrices(options, "m");
    ASSERT_EQ(jittered.size(), orbit.size());
    bool moved = false;
    for (std::size_t i = 0; i < orbit.size(); ++i) {
        expectRigid(jittered[i]);
        const glm::vec3 a = glm::normalize(position(orbit[i]));
        const glm::vec3 b = glm::normalize(position(jittered[i]));
        // Up to 10 degrees in each of azimuth and elevation: at most about 14 apart.
        EXPECT_LE(std::acos(std::min(1.0f, glm::dot(a, b))), glm::radians(14.2f)) << i;
        EXPECT_LE(std::abs(std::asin(b.y) - std::asin(a.y)), glm::radians(10.0f) + 1e-5f) << i;
        moved = moved || glm::dot(a, b) < 0.9999f;
        EXPECT_NEAR(glm::dot(forward(jittered[i]), -b), 1.0f, 1e-5f);
    }
    EXPECT_TRUE(moved);
    EXPECT_EQ(viewMatrices(options, "m"), jittered);
}

TEST(ViewRigTest, NormalizationPutsTheBoundsInTheUnitBox) {
    scene::Bounds bounds;
    bounds.extend({1.0f, 2.0f, 3.0f});
    bounds.extend({5.0f, 4.0f, 3.5f});
    const glm::mat4 n = normalization(bounds, true);
    const scene::Bounds unit = bounds.transformed(n);
    EXPECT_NEAR(unit.min.x, -0.5f, kEpsilon);
    EXPECT_NEAR(unit.max.x, 0.5f, kEpsilon);
    EXPECT_NEAR(unit.min.y, -0.25f, kEpsilon);
    EXPECT_NEAR(unit.max.z, 0.0625f, kEpsilon);
    EXPECT_EQ(normalization(bounds, false), glm::mat4(1.0f));
    EXPECT_EQ(normalization(scene::Bounds{}, true), glm::mat4(1.0f));
}

TEST(ViewRigTest, RenderCameraSeesTheNormalisedModelAsTheTransformsSay) {
    scene::Bounds bounds;
    bounds.extend({2.0f, 2.0f, 2.0f});
    bounds.extend({4.0f, 4.0f, 4.0f});
    const glm::mat4 n = normalization(bounds, true);
    ViewRigOptions options;
    const auto views = viewMatrices(options);
    const float fov = glm::radians(options.horizontalFovDegrees.min);
    const float aspect = 4.0f / 3.0f;
    for (const glm::mat4& cameraToWorld : views) {
        const render::Camera camera = renderCamera(cameraToWorld, n, fov, aspect);
        // The pinhole of transforms.json, applied to the normalised point.
        const glm::mat4 expected =
            render::perspectiveProjection(verticalFov(fov, aspect), aspect, 0.015f, 0.0f) *
            glm::inverse(cameraToWorld);
        for (const glm::vec3 point : {glm::vec3(3.0f), glm::vec3(4.0f, 2.0f, 4.0f)}) {
            glm::vec4 clip = camera.viewProjection() * glm::vec4(point, 1.0f);
            glm::vec4 reference = expected * n * glm::vec4(point, 1.0f);
            EXPECT_NEAR(clip.x / clip.w, reference.x / reference.w, 1e-4f);
            EXPECT_NEAR(clip.y / clip.w, reference.y / reference.w, 1e-4f);
        }
        // The model's centre is in the middle of the picture.
        const glm::vec4 centre = camera.viewProjection() * glm::vec4(3.0f, 3.0f, 3.0f, 1.0f);
        EXPECT_NEAR(centre.x / centre.w, 0.0f, 1e-5f);
        EXPECT_NEAR(centre.y / centre.w, 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(camera.position - glm::vec3(3.0f)), 3.0f, 1e-4f);
    }
}

TEST(ViewRigTest, HorizontalFieldOfViewSpansTheWidth) {
    // 35 mm lens, 32 mm sensor.
    EXPECT_NEAR(glm::radians(kDefaultHorizontalFovDegrees), 2.0 * std::atan(16.0 / 35.0), 1e-5);
    EXPECT_NEAR(verticalFov(glm::radians(90.0f), 2.0f), 2.0f * std::atan(0.5f), kEpsilon);
    const render::Camera camera =
        renderCamera(lookAtCameraToWorld({0.0f, 0.0f, 1.0f}, glm::vec3(0.0f)), glm::mat4(1.0f),
                     glm::radians(90.0f), 2.0f);
    // A point at 45 degrees to the right lands on the right edge.
    const glm::vec4 edge = camera.viewProjection() * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(edge.x / edge.w, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace encore::batch
