// The CPU side of the pass conventions (docs/batch.md#conventions): ray lengths, the unit of
// depth, camera-space normal rotations and object coordinates, on values worked out by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "batch/DepthConventions.h"
#include "batch/NormalConventions.h"
#include "batch/ObjectCoordinates.h"
#include "batch/PassImages.h"
#include "batch/RgbaPng.h"
#include "batch/TransformsJson.h"

namespace encore::batch {
namespace {

// A camera at (0, 0, 2) looking at the origin (OpenGL axes), 90 degrees across.
ViewCamera frontCamera() {
    ViewCamera view;
    view.cameraToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f));
    view.horizontalFovRadians = glm::radians(90.0f);
    return view;
}

TEST(PassConventionsTest, RaysAreLongerByOneOverTheCosineOfTheirAngle) {
    const ViewCamera view = frontCamera();
    // 4 x 4 at 90 degrees: f = 2 pixels; pixel (0, 0)'s centre is 1.5 pixels off on each axis.
    EXPECT_NEAR(rayLengthPerDepth(view, 4, 4, 0, 0), std::sqrt(1.0 + 2.0 * 0.75 * 0.75), 1e-6);
    EXPECT_NEAR(rayLengthPerDepth(view, 4, 4, 2, 1), std::sqrt(1.0 + 0.25 * 0.25 + 0.25 * 0.25),
                1e-6);
    ViewCamera orthographic = view;
    orthographic.projection = Projection::Orthographic;
    orthographic.orthoScale = 1.0f;
    EXPECT_EQ(rayLengthPerDepth(orthographic, 4, 4, 0, 0), 1.0);

    std::vector<float> depth(16, 2.0f);
    depth[5] = std::numeric_limits<float>::infinity();
    depthAlongRays(depth, view, 4, 4);
    EXPECT_NEAR(depth[0], 2.0 * std::sqrt(1.0 + 2.0 * 0.75 * 0.75), 1e-6);
    EXPECT_TRUE(std::isinf(depth[5]));
    // The steps of a 16-bit image: empty stays 0, anything else at least 1.
    const image::ImageGray16 steps = depthStepsOf(depth, 4, 4, 0.001);
    EXPECT_EQ(steps.pixels[5], 0);
    EXPECT_EQ(steps.pixels[0], std::lround(depth[0] / 0.001));
    EXPECT_EQ(depthUnitsPerModelUnit(DepthUnit::Model, 0.25f), 1.0f);
    EXPECT_EQ(depthUnitsPerModelUnit(DepthUnit::Normalized, 0.25f), 0.25f);
}

TEST(PassConventionsTest, CameraSpaceNormalsInEachConvention) {
    // Turned 90 degrees about +Y: the camera at +X looks along -X; its +Z (OpenGL) is world +X.
    ViewCamera view = frontCamera();
    view.cameraToWorld = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {0.0f, 1.0f, 0.0f});
    const glm::dvec3 towardCamera(1.0, 0.0, 0.0);
    const glm::dvec3 up(0.0, 1.0, 0.0);
    const auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-6; };
    const glm::dmat3 gl = normalRotation(view, NormalSpace::Camera, CameraConvention::OpenGl);
    EXPECT_TRUE(near(gl * towardCamera, {0, 0, 1}));
    EXPECT_TRUE(near(gl * up, {0, 1, 0}));
    const glm::dmat3 cv = normalRotation(view, NormalSpace::Camera, CameraConvention::OpenCv);
    EXPECT_TRUE(near(cv * towardCamera, {0, 0, -1}));
    EXPECT_TRUE(near(cv * up, {0, -1, 0}));
    const glm::dmat3 blender = normalRotation(view, NormalSpace::Camera, CameraConvention::Blender);
    EXPECT_TRUE(near(blender * towardCamera, {0, 0, 1}));
    const glm::dmat3 world = normalRotation(view, NormalSpace::World, CameraConvention::OpenCv);
    EXPECT_TRUE(near(world * towardCamera, towardCamera));
}

TEST(PassConventionsTest, NormalsAndCoordinatesUndoTheCoverage) {
    // Two texels: n = +X at half coverage (blended over black), and nothing.
    const std::vector<float> texels = {0.5f, 0.25f, 0.25f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f};
    const FloatStrip strip{texels, 2, 0, 2, 1};
    const std::vector<float> normals = normalVectors(strip, glm::dmat3(1.0));
    EXPECT_NEAR(normals[0], 1.0f, 1e-6f);
    EXPECT_NEAR(normals[1], 0.0f, 1e-6f);
    EXPECT_EQ(normals[3], 0.5f);
    EXPECT_EQ(normals[7], 0.0f);

    // Positions (4, 2, 0) at full coverage in a model of bounds (0..8, 0..4, 0..2): scale 1/8,
    // centre (4, 2, 1), so (0.5, 0.5, 0.5 - 1/8).
    const std::vector<float> positions = {4.0f, 2.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    const glm::mat4 box = glm::scale(glm::mat4(1.0f), glm::vec3(0.125f)) *
                          glm::translate(glm::mat4(1.0f), glm::vec3(-4.0f, -2.0f, -1.0f));
    const std::vector<float> coordinates =
        objectCoordinates(FloatStrip{positions, 2, 0, 2, 1}, box);
    EXPECT_NEAR(coordinates[0], 0.5f, 1e-6f);
    EXPECT_NEAR(coordinates[1], 0.5f, 1e-6f);
    EXPECT_NEAR(coordinates[2], 0.375f, 1e-6f);
    EXPECT_EQ(coordinates[3], 1.0f);
    EXPECT_EQ(coordinates[4], 0.0f);
    EXPECT_EQ(coordinates[7], 0.0f);
}

TEST(PassConventionsTest, DepthOfAKindFromTheDepthChannel) {
    // Pixel (0, 0) of a 4 x 4 view at 90 degrees: depth 4 model units at half coverage; (1, 0)
    // a third covered (empty); the rest nothing.
    std::vector<float> texels(4 * 4 * 4, 0.0f);
    texels[0] = 2.0f;
    texels[3] = 0.5f;
    texels[4] = 1.0f;
    texels[7] = 1.0f / 3.0f;
    const FloatStrip strip{texels, 4, 0, 4, 4};
    const ViewCamera view = frontCamera();
    const std::vector<float> z = depthOfKind(strip, DepthKind::Z, 0.5f, view);
    EXPECT_EQ(z[0], 2.0f);
    EXPECT_TRUE(std::isinf(z[1]));
    const std::vector<float> ray = depthOfKind(strip, DepthKind::Ray, 0.5f, view);
    EXPECT_NEAR(ray[0], 2.0 * std::sqrt(1.0 + 2.0 * 0.75 * 0.75), 1e-6);
    EXPECT_TRUE(std::isinf(ray[1]));
}

TEST(PassConventionsTest, NormalsAsAPngStoresThem) {
    const std::vector<float> normals = {0.0f, -1.0f, 1.0f, 0.5f, 0.3f, 0.3f, 0.3f, 0.0f};
    const std::vector<float> mapped = mappedNormals(normals);
    EXPECT_EQ(mapped, (std::vector<float>{0.5f, 0.0f, 1.0f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f}));
    EXPECT_EQ(pngSample(0.5f, 8), 128u);
    EXPECT_EQ(pngSample(0.5f, 16), 32768u);
    EXPECT_EQ(pngSample(1.5f, 16), 65535u);
    EXPECT_EQ(pngSample(-0.5f, 8), 0u);
    ExtraImages images;
    images.normalKind = NormalKind::Geometric;
    EXPECT_EQ(passChannel(ViewImage::Normal, images), render::DebugChannel::GeometricNormal);
    EXPECT_EQ(passChannel(ViewImage::Depth, images), render::DebugChannel::Depth);
    images.segmentationBy = SegmentationBy::Mesh;
    EXPECT_EQ(passChannel(ViewImage::Segmentation, images), render::DebugChannel::SegmentMesh);
}

}  // namespace
}  // namespace encore::batch
