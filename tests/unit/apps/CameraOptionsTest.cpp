// The shared camera options of the encore subcommands: parsing and validation of the flags, and
// which camera resolveCamera builds from them (no GPU).

#include "CameraOptions.h"

#include <gtest/gtest.h>

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

namespace encore::app {
namespace {

bool sameBytes(const glm::mat4& a, const glm::mat4& b) {
    return std::memcmp(&a, &b, sizeof(glm::mat4)) == 0;
}

void expectSameCamera(const render::Camera& actual, const render::Camera& expected) {
    EXPECT_TRUE(sameBytes(actual.view, expected.view));
    EXPECT_TRUE(sameBytes(actual.projection, expected.projection));
    EXPECT_EQ(actual.position, expected.position);
    EXPECT_EQ(actual.kind, expected.kind);
    EXPECT_EQ(actual.nearPlane, expected.nearPlane);
    EXPECT_EQ(actual.farPlane, expected.farPlane);
}

// A scene with a named perspective camera, an unnamed orthographic one and a box of bounds.
scene::SceneData sceneWithCameras() {
    scene::SceneData scene;
    scene.sourcePath = "cameras.gltf";
    scene.bounds.extend(glm::vec3(-1.0f, 0.0f, -2.0f));
    scene.bounds.extend(glm::vec3(3.0f, 1.0f, 2.0f));
    scene::CameraData front;
    front.name = "Front";
    front.yfov = 0.6f;
    front.znear = 0.1f;
    front.zfar = 0.0f;
    scene::CameraData top;
    top.projection = scene::CameraProjection::Orthographic;
    top.xmag = 2.0f;
    top.ymag = 1.5f;
    top.znear = 0.5f;
    top.zfar = 50.0f;
    scene.cameras = {front, top};
    scene::CameraInstance frontInstance;
    frontInstance.camera = scene::CameraId(std::uint32_t(0));
    frontInstance.node = scene::NodeId(std::uint32_t(3));
    frontInstance.world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 8.0f));
    scene::CameraInstance topInstance;
    topInstance.camera = scene::CameraId(std::uint32_t(1));
    topInstance.node = scene::NodeId(std::uint32_t(4));
    topInstance.world =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 10.0f, 0.0f)) *
        glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    scene.cameraInstances = {frontInstance, topInstance};
    return scene;
}

TEST(CameraOptionsTest, DefaultsToTheFraming) {
    const auto scene = sceneWithCameras();
    CameraOptions options;
    auto camera = resolveCamera(options, scene, 1.5f);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    expectSameCamera(*camera, render::Camera::framing(scene.bounds, 1.5f));

    options.yawDegrees = 30.0f;
    expectSameCamera(*resolveCamera(options, scene, 1.5f),
                     render::Camera::framing(scene.bounds, 1.5f, glm::radians(30.0f)));

    options.yfovDegrees = 60.0f;
    options.zfar = 500.0f;
    auto wider = resolveCamera(options, scene, 1.5f);
    ASSERT_TRUE(wider.ok()) << wider.error().message;
    const auto framed =
        render::Camera::framing(scene.bounds, 1.5f, glm::radians(30.0f), glm::radians(60.0f));
    EXPECT_TRUE(sameBytes(wider->view, framed.view));
    EXPECT_EQ(wider->nearPlane, framed.nearPlane);
    EXPECT_EQ(wider->farPlane, 500.0f);
    EXPECT_TRUE(sameBytes(wider->projection, glm::perspectiveRH_ZO(glm::radians(60.0f), 1.5f,
                                                                   framed.nearPlane, 500.0f)));
}

TEST(CameraOptionsTest, PicksGltfCamerasByIndexOrName) {
    const auto scene = sceneWithCameras();
    CameraOptions options;
    options.camera = "Front";
    auto byName = resolveCamera(options, scene, 2.0f);
    ASSERT_TRUE(byName.ok()) << byName.error().message;
    expectSameCamera(
        *byName, render::Camera::fromGltf(scene.cameras[0], scene.cameraInstances[0].world, 2.0f));
    EXPECT_TRUE(byName->infiniteFar());

    options.camera = "1";
    auto byIndex = resolveCamera(options, scene, 2.0f);
    ASSERT_TRUE(byIndex.ok()) << byIndex.error().message;
    expectSameCamera(
        *byIndex, render::Camera::fromGltf(scene.cameras[1], scene.cameraInstances[1].world, 2.0f));
    EXPECT_EQ(byIndex->kind, render::ProjectionKind::Orthographic);

    // Overrides of the file's values.
    options.camera = "0";
    options.yfovDegrees = 90.0f;
    options.znear = 0.25f;
    options.zfar = 40.0f;
    auto overridden = resolveCamera(options, scene, 2.0f);
    ASSERT_TRUE(overridden.ok()) << overridden.error().message;
    EXPECT_TRUE(sameBytes(overridden->projection,
                          glm::perspectiveRH_ZO(glm::radians(90.0f), 2.0f, 0.25f, 40.0f)));
}

TEST(CameraOptionsTest, MissingCamerasAreExplained) {
    auto scene = sceneWithCameras();
    CameraOptions options;
    options.camera = "Side";
    auto missing = resolveCamera(options, scene, 1.0f);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(missing.error().message,
              "cameras.gltf: there is no camera 'Side' (the cameras are: 0 'Front' (perspective), "
              "1 (orthographic)).");
    options.camera = "2";
    EXPECT_FALSE(resolveCamera(options, scene, 1.0f).ok());

    options.camera = "1";
    options.yfovDegrees = 50.0f;
    auto orthographicFov = resolveCamera(options, scene, 1.0f);
    ASSERT_FALSE(orthographicFov.ok());
    EXPECT_NE(orthographicFov.error().message.find("orthographic"), std::string::npos);

    scene.cameraInstances.clear();
    options.yfovDegrees.reset();
    auto none = resolveCamera(options, scene, 1.0f);
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().message.find("places no cameras"), std::string::npos)
        << none.error().message;
}

TEST(CameraOptionsTest, ExplicitViewpointLooksAtTheTarget) {
    const auto scene = sceneWithCameras();
    CameraOptions options;
    options.position = glm::vec3(0.0f, 0.0f, 10.0f);
    options.target = glm::vec3(0.0f, 0.0f, 0.0f);
    auto camera = resolveCamera(options, scene, 1.0f);
    ASSERT_TRUE(camera.ok()) << camera.error().message;
    // 45 degrees, near at 1/1000 of the distance, infinite far.
    expectSameCamera(*camera,
                     render::Camera::lookAt(*options.position, *options.target, glm::radians(45.0f),
                                            1.0f, 10.0f * kDefaultNearFraction, 0.0f));
    EXPECT_TRUE(camera->infiniteFar());

    options.znear = 2.0f;
    options.zfar = 1.0f;
    auto inverted = resolveCamera(options, scene, 1.0f);
    ASSERT_FALSE(inverted.ok());
    EXPECT_EQ(inverted.error().code, ErrorCode::InvalidArgument);

    options.znear.reset();
    options.zfar.reset();
    options.target = options.position;
    EXPECT_FALSE(resolveCamera(options, scene, 1.0f).ok());
}

TEST(CameraOptionsTest, ParsesAndValidatesTheFlags) {
    auto parse = [](const std::string& arguments, CameraOptions& options) {
        CLI::App app;
        addCameraOptions(app, options);
        app.parse(arguments, false);
    };
    CameraOptions options;
    parse("--camera-position=-1,2.5,3 --target 0,0,-4e1 --yfov 30 --znear 0.5 --zfar 90", options);
    ASSERT_TRUE(options.position && options.target);
    EXPECT_EQ(*options.position, glm::vec3(-1.0f, 2.5f, 3.0f));
    EXPECT_EQ(*options.target, glm::vec3(0.0f, 0.0f, -40.0f));
    EXPECT_EQ(options.yfovDegrees, 30.0f);
    EXPECT_EQ(options.znear, 0.5f);
    EXPECT_EQ(options.zfar, 90.0f);

    CameraOptions named;
    parse("--camera Front", named);
    EXPECT_EQ(named.camera, "Front");
    EXPECT_FALSE(named.position);

    for (const char* bad :
         {"--camera-position 1,2,3",  // Without --target.
          "--target 1,2,3", "--camera 0 --camera-position 1,2,3 --target 0,0,0",
          "--camera-position 1,2 --target 0,0,0", "--camera-position 1,2,3,4 --target 0,0,0",
          "--camera-position 1,x,3 --target 0,0,0", "--yfov 0", "--yfov 180", "--yfov -5",
          "--znear 0", "--znear -1", "--zfar nan"}) {
        SCOPED_TRACE(bad);
        CameraOptions ignored;
        EXPECT_THROW(parse(bad, ignored), CLI::ParseError);
    }
}

}  // namespace
}  // namespace encore::app
