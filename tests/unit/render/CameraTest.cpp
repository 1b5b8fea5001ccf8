// Camera projections in WebGPU clip space (no GPU): depth range, infinite far planes,
// orthographic extents, glTF camera rules, node orientation and the frustum planes the GPU
// culler extracts from them.

#include "encore/render/Camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "encore/scene/SceneData.h"
#include "render/culling/Frustum.h"

namespace encore::render {
namespace {

// Normalised device coordinates of a world point (x, y in -1..1, z = depth 0..1).
glm::vec3 ndcOf(const Camera& camera, const glm::vec4& point) {
    const glm::vec4 clip = camera.viewProjection() * point;
    return glm::vec3(clip) / clip.w;
}

glm::vec3 ndcOf(const Camera& camera, const glm::vec3& point) {
    return ndcOf(camera, glm::vec4(point, 1.0f));
}

bool sameBytes(const glm::mat4& a, const glm::mat4& b) {
    return std::memcmp(&a, &b, sizeof(glm::mat4)) == 0;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(CameraTest, FiniteLookAtIsGlmsRightHandedZeroToOne) {
    const glm::vec3 eye(1.0f, 2.0f, 3.0f);
    const glm::vec3 target(0.0f, 0.5f, -1.0f);
    const Camera camera = Camera::lookAt(eye, target, 0.9f, 1.5f, 0.1f, 50.0f);
    EXPECT_TRUE(sameBytes(camera.view, glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f))));
    EXPECT_TRUE(sameBytes(camera.projection, glm::perspectiveRH_ZO(0.9f, 1.5f, 0.1f, 50.0f)));
    EXPECT_EQ(camera.position, eye);
    EXPECT_EQ(camera.kind, ProjectionKind::Perspective);
    EXPECT_EQ(camera.nearPlane, 0.1f);
    EXPECT_EQ(camera.farPlane, 50.0f);
    EXPECT_FALSE(camera.infiniteFar());

    const glm::vec3 forward = glm::normalize(target - eye);
    EXPECT_NEAR(ndcOf(camera, eye + forward * 0.1f).z, 0.0f, 1e-5f);
    EXPECT_NEAR(ndcOf(camera, eye + forward * 50.0f).z, 1.0f, 1e-5f);
    expectNear(ndcOf(camera, target), glm::vec3(0.0f, 0.0f, ndcOf(camera, target).z), 1e-6f);
}

TEST(CameraTest, InfiniteFarKeepsFarPointsInFrontOfTheClearedDepth) {
    for (float farPlane : {0.0f, -1.0f, std::numeric_limits<float>::infinity()}) {
        SCOPED_TRACE(farPlane);
        const Camera camera = Camera::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 1.0f,
                                             1.0f, 0.01f, farPlane);
        EXPECT_TRUE(camera.infiniteFar());
        EXPECT_TRUE(std::isinf(camera.farPlane));
        EXPECT_NEAR(ndcOf(camera, glm::vec3(0.0f, 0.0f, -0.01f)).z, 0.0f, 1e-6f);
        float previous = 0.0f;
        // Up to 1e9 near-plane distances, far beyond float's 2^24 steps below 1. Past 1e4 the
        // depths differ by less than a float step, so they only must not decrease.
        for (float distance : {1.0f, 100.0f, 1e4f, 1e5f, 1e6f, 1e7f}) {
            const float depth = ndcOf(camera, glm::vec3(0.0f, 0.0f, -distance)).z;
            EXPECT_LT(depth, 1.0f) << distance;  // Passes depth compare Less against 1.
            if (distance <= 1e4f) {
                EXPECT_GT(depth, previous) << distance;
            } else {
                EXPECT_GE(depth, previous) << distance;
            }
            EXPECT_NEAR(depth, (1.0f - 0.01f / distance) * kInfiniteDepthScale, 1e-6f);
            previous = depth;
        }
        // A direction (w = 0) is the point at infinity: depth ~1 but still below 1.
        const float infinity = ndcOf(camera, glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)).z;
        EXPECT_LT(infinity, 1.0f);
        EXPECT_GT(infinity, 1.0f - 1e-5f);
        // The lateral field of view is that of the finite projection.
        const glm::mat4 finite = glm::perspectiveRH_ZO(1.0f, 1.0f, 0.01f, 100.0f);
        EXPECT_EQ(camera.projection[0][0], finite[0][0]);
        EXPECT_EQ(camera.projection[1][1], finite[1][1]);
    }
}

TEST(CameraTest, OrthographicMapsMagnificationsAndClipDistances) {
    const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 10.0f));
    const Camera camera = Camera::orthographic(world, 3.0f, 2.0f, 0.5f, 20.0f);
    EXPECT_EQ(camera.kind, ProjectionKind::Orthographic);
    EXPECT_EQ(camera.nearPlane, 0.5f);
    EXPECT_EQ(camera.farPlane, 20.0f);
    EXPECT_EQ(camera.position, glm::vec3(1.0f, 2.0f, 10.0f));
    expectNear(ndcOf(camera, glm::vec3(1.0f + 3.0f, 2.0f + 2.0f, 9.5f)), {1.0f, 1.0f, 0.0f}, 1e-5f);
    expectNear(ndcOf(camera, glm::vec3(1.0f - 3.0f, 2.0f - 2.0f, -10.0f)), {-1.0f, -1.0f, 1.0f},
               1e-5f);
    // Parallel projection: the same lateral offset lands on the same pixel at any depth.
    EXPECT_NEAR(ndcOf(camera, glm::vec3(2.5f, 2.0f, 5.0f)).x,
                ndcOf(camera, glm::vec3(2.5f, 2.0f, -5.0f)).x, 1e-6f);
    // glTF's orthographic matrix, with depth 0..1.
    EXPECT_FLOAT_EQ(camera.projection[0][0], 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(camera.projection[1][1], 1.0f / 2.0f);
    EXPECT_FLOAT_EQ(camera.projection[2][2], 1.0f / (0.5f - 20.0f));
    EXPECT_FLOAT_EQ(camera.projection[3][2], 0.5f / (0.5f - 20.0f));
    EXPECT_EQ(camera.projection[2][3], 0.0f);

    // An invalid zfar (glTF forbids it) still gives a finite matrix.
    const Camera invalid = Camera::orthographic(glm::mat4(1.0f), 1.0f, 1.0f, 2.0f, 0.0f);
    EXPECT_TRUE(std::isfinite(invalid.projection[2][2]));
}

TEST(CameraTest, NodeCamerasLookDownTheirMinusZWithPlusYUp) {
    // Turned 90 degrees about +Y: the node's -Z axis is world -X.
    const glm::mat4 world =
        glm::translate(glm::mat4(1.0f), glm::vec3(4.0f, 1.0f, 0.0f)) *
        glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const Camera camera = Camera::perspective(world, 0.8f, 1.0f, 0.1f, 100.0f);
    EXPECT_EQ(camera.position, glm::vec3(4.0f, 1.0f, 0.0f));
    const glm::vec3 ahead = ndcOf(camera, glm::vec3(0.0f, 1.0f, 0.0f));
    expectNear(glm::vec3(ahead.x, ahead.y, 0.0f), glm::vec3(0.0f), 1e-5f);
    EXPECT_GT(ahead.z, 0.0f);
    EXPECT_LT(ahead.z, 1.0f);
    EXPECT_GT(ndcOf(camera, glm::vec3(0.0f, 2.0f, 0.0f)).y, 0.0f);  // Above is up.
    // The node's +X (world -Z) is the right of the picture.
    EXPECT_GT(ndcOf(camera, glm::vec3(0.0f, 1.0f, -1.0f)).x, 0.0f);
    // Behind the camera: w < 0.
    EXPECT_LT((camera.viewProjection() * glm::vec4(8.0f, 1.0f, 0.0f, 1.0f)).w, 0.0f);
    // view = inverse(world) for a rigid world matrix.
    const glm::mat4 inverse = glm::inverse(world);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(camera.view[c][r], inverse[c][r], 1e-5f);
        }
    }
    // Scale on the node does not scale the view.
    const Camera scaled = Camera::perspective(
        world * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 3.0f, 0.5f)), 0.8f, 1.0f, 0.1f, 100.0f);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(scaled.view[c][r], inverse[c][r], 1e-5f);
        }
    }
}

TEST(CameraTest, GltfPerspectiveKeepsYfovAndUsesTheTargetAspect) {
    scene::CameraData data;
    data.projection = scene::CameraProjection::Perspective;
    data.yfov = 0.7f;
    data.znear = 0.05f;
    data.zfar = 0.0f;  // Absent: infinite.
    const glm::mat4 world(1.0f);

    const Camera noAspect = Camera::fromGltf(data, world, 1.5f);
    EXPECT_TRUE(noAspect.infiniteFar());
    EXPECT_FLOAT_EQ(noAspect.projection[1][1], 1.0f / std::tan(0.35f));
    EXPECT_FLOAT_EQ(noAspect.projection[0][0], noAspect.projection[1][1] / 1.5f);
    EXPECT_EQ(noAspect.nearPlane, 0.05f);

    data.aspectRatio = 2.0f;  // Differs from the target's: vertical field kept, no stretching.
    const Camera authored = Camera::fromGltf(data, world, 1.5f);
    EXPECT_FLOAT_EQ(authored.projection[1][1], 1.0f / std::tan(0.35f));
    EXPECT_FLOAT_EQ(authored.projection[0][0], authored.projection[1][1] / 1.5f);

    // Without a usable target aspect, the file's.
    EXPECT_FLOAT_EQ(Camera::fromGltf(data, world, 0.0f).projection[0][0],
                    authored.projection[1][1] / 2.0f);

    data.zfar = 30.0f;
    const Camera finite = Camera::fromGltf(data, world, 1.5f);
    EXPECT_FALSE(finite.infiniteFar());
    EXPECT_TRUE(sameBytes(finite.projection, glm::perspectiveRH_ZO(0.7f, 1.5f, 0.05f, 30.0f)));
}

TEST(CameraTest, GltfOrthographicUsesMagnificationsAsGiven) {
    scene::CameraData data;
    data.projection = scene::CameraProjection::Orthographic;
    data.xmag = 4.0f;
    data.ymag = 1.0f;
    data.znear = 0.0f;
    data.zfar = 10.0f;
    for (float aspect : {1.0f, 16.0f / 9.0f}) {
        const Camera camera = Camera::fromGltf(data, glm::mat4(1.0f), aspect);
        EXPECT_EQ(camera.kind, ProjectionKind::Orthographic);
        EXPECT_FLOAT_EQ(camera.projection[0][0], 0.25f);
        EXPECT_FLOAT_EQ(camera.projection[1][1], 1.0f);
        EXPECT_EQ(camera.farPlane, 10.0f);
    }
}

bool visible(const Frustum& frustum, const glm::vec3& center, float radius) {
    return frustum.intersects(Sphere(center, radius));
}

void expectFinitePlanes(const Frustum& frustum) {
    for (const glm::vec4& plane : frustum.planes) {
        EXPECT_TRUE(std::isfinite(plane.x) && std::isfinite(plane.y) && std::isfinite(plane.z) &&
                    std::isfinite(plane.w));
    }
}

TEST(CameraTest, OrthographicFrustumBoundsTheBox) {
    const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 10.0f));
    const Camera camera = Camera::orthographic(world, 3.0f, 2.0f, 1.0f, 20.0f);
    const Frustum frustum = Frustum::fromViewProjection(camera.viewProjection());
    expectFinitePlanes(frustum);
    EXPECT_TRUE(visible(frustum, {0.0f, 0.0f, 0.0f}, 0.1f));
    EXPECT_TRUE(visible(frustum, {2.9f, 1.9f, -9.5f}, 0.05f));  // Near the far corner.
    EXPECT_FALSE(visible(frustum, {3.5f, 0.0f, 0.0f}, 0.4f));   // Right of xmag.
    EXPECT_FALSE(visible(frustum, {-3.5f, 0.0f, 0.0f}, 0.4f));
    EXPECT_FALSE(visible(frustum, {0.0f, 2.5f, 0.0f}, 0.4f));    // Above ymag.
    EXPECT_TRUE(visible(frustum, {0.0f, 2.5f, 0.0f}, 0.6f));     // Overlaps the top plane.
    EXPECT_FALSE(visible(frustum, {0.0f, 0.0f, 9.5f}, 0.4f));    // Nearer than znear.
    EXPECT_FALSE(visible(frustum, {0.0f, 0.0f, -10.5f}, 0.4f));  // Beyond zfar.
    // The planes are unit planes: distances are in world units.
    EXPECT_NEAR(glm::dot(glm::vec3(frustum.planes[0]), glm::vec3(0.0f)) + frustum.planes[0].w, 3.0f,
                1e-5f);
}

TEST(CameraTest, InfiniteFrustumCullsSidesAndBehindButNothingFar) {
    const Camera camera = Camera::lookAt({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f},
                                         glm::radians(60.0f), 1.0f, 0.1f, 0.0f);
    const Frustum frustum = Frustum::fromViewProjection(camera.viewProjection());
    expectFinitePlanes(frustum);
    EXPECT_EQ(frustum.planes[5], glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // No far plane.
    for (float distance : {1.0f, 1e3f, 1e6f, 1e9f, 1e20f}) {
        EXPECT_TRUE(visible(frustum, {0.0f, 0.0f, -distance}, 0.0f)) << distance;
    }
    EXPECT_FALSE(visible(frustum, {0.0f, 0.0f, 2.0f}, 1.0f));       // Behind.
    EXPECT_FALSE(visible(frustum, {0.0f, 0.0f, -0.05f}, 0.01f));    // Nearer than znear.
    EXPECT_FALSE(visible(frustum, {100.0f, 0.0f, -10.0f}, 1.0f));   // Far to the right.
    EXPECT_FALSE(visible(frustum, {0.0f, -100.0f, -10.0f}, 1.0f));  // Far below.
    EXPECT_TRUE(visible(frustum, {5.0f, 0.0f, -10.0f}, 0.5f));      // tan(30) * 10 = 5.77.

    // A finite camera keeps its far plane.
    const Camera finite = Camera::lookAt({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f},
                                         glm::radians(60.0f), 1.0f, 0.1f, 100.0f);
    const Frustum bounded = Frustum::fromViewProjection(finite.viewProjection());
    EXPECT_TRUE(visible(bounded, {0.0f, 0.0f, -99.0f}, 0.5f));
    EXPECT_FALSE(visible(bounded, {0.0f, 0.0f, -102.0f}, 1.0f));
    EXPECT_NEAR(bounded.planes[5].w, 100.0f, 1e-3f);
}

TEST(CameraTest, FramingIsUnchanged) {
    scene::Bounds bounds;
    bounds.min = glm::vec3(-1.0f, 0.0f, -2.0f);
    bounds.max = glm::vec3(3.0f, 1.0f, 2.0f);
    const Camera camera = Camera::framing(bounds, 1.25f, 0.3f);
    const Camera explicitFov = Camera::framing(bounds, 1.25f, 0.3f, glm::radians(45.0f));
    EXPECT_TRUE(sameBytes(camera.view, explicitFov.view));
    EXPECT_TRUE(sameBytes(camera.projection, explicitFov.projection));
    EXPECT_FALSE(camera.infiniteFar());
    EXPECT_GT(camera.farPlane, camera.nearPlane);
    // Every corner of the box is inside the picture and the depth range.
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 point((corner & 1) ? bounds.max.x : bounds.min.x,
                              (corner & 2) ? bounds.max.y : bounds.min.y,
                              (corner & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 ndc = ndcOf(camera, point);
        EXPECT_LE(std::abs(ndc.x), 1.0f);
        EXPECT_LE(std::abs(ndc.y), 1.0f);
        EXPECT_GT(ndc.z, 0.0f);
        EXPECT_LT(ndc.z, 1.0f);
    }
}

bool isFinite(const glm::mat4& matrix) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(matrix[c][r])) {
                return false;
            }
        }
    }
    return true;
}

// Empty boxes, boxes whose centre or size overflows a float, and boxes built by hand with NaN
// or infinity all give a finite camera.
TEST(CameraTest, FramingStaysFiniteForEmptyHugeAndNonFiniteBounds) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float big = std::numeric_limits<float>::max();
    std::vector<scene::Bounds> boxes(5);
    boxes[1].extend(glm::vec3(-big));
    boxes[1].extend(glm::vec3(big));
    boxes[2].min = glm::vec3(0.0f, nan, 0.0f);
    boxes[2].max = glm::vec3(1.0f);
    boxes[3].min = glm::vec3(-inf);
    boxes[3].max = glm::vec3(inf);
    boxes[4].extend(glm::vec3(big * 0.9f, 0.0f, 0.0f));
    boxes[4].extend(glm::vec3(big, 1.0f, 1.0f));
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Camera camera = Camera::framing(boxes[i], 1.5f, 0.0f);
        EXPECT_TRUE(isFinite(camera.view)) << "box " << i;
        EXPECT_TRUE(isFinite(camera.projection)) << "box " << i;
        EXPECT_TRUE(std::isfinite(camera.nearPlane) && std::isfinite(camera.farPlane))
            << "box " << i;
        EXPECT_GT(camera.farPlane, camera.nearPlane) << "box " << i;
    }
}

}  // namespace
}  // namespace encore::render
