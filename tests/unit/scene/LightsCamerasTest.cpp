// KHR_lights_punctual lights and glTF cameras: parsed values, defaults, validation, and their
// placement in world space by the nodes of the chosen scene.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "SceneTestUtils.h"
#include "TestPaths.h"

namespace encore::scene {
namespace {

using nlohmann::json;
using testing::expectError;
using testing::loadGltf;
using testing::triangleBuilder;

constexpr float kPi = 3.14159265358979f;

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
    }
}

void expectNear(const glm::mat4& actual, const glm::mat4& expected, float tolerance = 1e-5f) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "column " << c << ", row " << r;
        }
    }
}

// The triangle scene plus the given lights in the root KHR_lights_punctual extension.
test::GltfBuilder lightsBuilder(const json& lights) {
    auto builder = triangleBuilder();
    builder.json()["extensionsUsed"] = {"KHR_lights_punctual"};
    builder.json()["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    return builder;
}

void placeLight(test::GltfBuilder& builder, std::uint32_t node, int light) {
    builder.json()["nodes"][node]["extensions"]["KHR_lights_punctual"] = {{"light", light}};
}

TEST(LightsCamerasTest, LightsParseWithDefaults) {
    auto builder = lightsBuilder(json::array({
        {{"type", "directional"}, {"name", "sun"}, {"color", {1, 0.5, 0.25}}, {"intensity", 3}},
        {{"type", "point"}, {"range", 10}},
        {{"type", "spot"},
         {"intensity", 0},
         {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
        {{"type", "spot"}},
        {{"type", "spot"}, {"spot", {{"outerConeAngle", kPi / 2}}}},
    }));
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 5u);
    const auto& lights = scene->lights;
    EXPECT_EQ(lights[0].name, "sun");
    EXPECT_EQ(lights[0].type, LightType::Directional);
    EXPECT_EQ(lights[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(lights[0].intensity, 3.0f);
    EXPECT_EQ(lights[0].range, 0.0f);
    EXPECT_EQ(lights[1].type, LightType::Point);
    EXPECT_EQ(lights[1].color, glm::vec3(1.0f));
    EXPECT_EQ(lights[1].intensity, 1.0f);
    EXPECT_EQ(lights[1].range, 10.0f);
    EXPECT_EQ(lights[2].type, LightType::Spot);
    EXPECT_EQ(lights[2].intensity, 0.0f);
    EXPECT_EQ(lights[2].innerConeAngle, 0.25f);
    EXPECT_EQ(lights[2].outerConeAngle, 0.5f);
    EXPECT_EQ(lights[3].innerConeAngle, 0.0f);
    EXPECT_FLOAT_EQ(lights[3].outerConeAngle, kPi / 4);
    EXPECT_FLOAT_EQ(lights[4].outerConeAngle, kPi / 2);
    EXPECT_TRUE(scene->lightInstances.empty());  // No node places them.
    EXPECT_EQ(scene->extensionsUsed, std::vector<std::string>{"KHR_lights_punctual"});
    EXPECT_TRUE(scene->extensionsIgnored.empty());
    EXPECT_TRUE(scene->warnings.empty());
}

TEST(LightsCamerasTest, LightsArePlacedInWorldSpace) {
    auto builder = lightsBuilder(json::array({{{"type", "spot"}}, {{"type", "point"}}}));
    // Node 1 (root): translated and turned 90 degrees about +Y, scaled by 2; node 2, its child,
    // moved one unit along the parent's +Z places light 0. Node 3, a root, places light 1.
    const glm::quat turn = glm::angleAxis(kPi / 2, glm::vec3(0, 1, 0));
    const auto child = builder.addNode({.translation = glm::vec3(0, 0, 1)});
    const auto parent = builder.addNode({.children = {child},
                                         .translation = glm::vec3(1, 2, 3),
                                         .rotation = turn,
                                         .scale = glm::vec3(2)});
    const auto other = builder.addNode({.translation = glm::vec3(-5, 0, 0)});
    builder.json()["scenes"][0]["nodes"] = {0, parent, other};
    placeLight(builder, child, 0);
    placeLight(builder, other, 1);
    // A node outside the scene places nothing.
    const auto outside = builder.addNode({});
    placeLight(builder, outside, 1);
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lightInstances.size(), 2u);
    const LightInstance& spot = scene->lightInstances[0];
    EXPECT_EQ(spot.light.value, 0u);
    EXPECT_EQ(spot.node.value, child);
    // +Z turned about +Y is +X, scaled by 2: (1, 2, 3) + (2, 0, 0).
    expectNear(spot.position, glm::vec3(3, 2, 3));
    // -Z turned about +Y is -X; the scale does not lengthen the direction.
    expectNear(spot.direction, glm::vec3(-1, 0, 0));
    const LightInstance& point = scene->lightInstances[1];
    EXPECT_EQ(point.light.value, 1u);
    EXPECT_EQ(point.node.value, other);
    expectNear(point.position, glm::vec3(-5, 0, 0));
    expectNear(point.direction, glm::vec3(0, 0, -1));
}

TEST(LightsCamerasTest, InvalidLightsAreErrors) {
    struct Case {
        const char* name;
        json light;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
        {"UnknownType", {{"type", "area"}}, {"light 0 has an unknown type ('area'"}},
        {"MissingType", {{"intensity", 1}}, {"light 0 lacks the required 'type'"}},
        {"NegativeIntensity",
         {{"type", "point"}, {"intensity", -2}},
         {"light 0 has an invalid intensity (-2", "negative"}},
        {"ZeroRange", {{"type", "point"}, {"range", 0}}, {"light 0 has an invalid range (0"}},
        {"NegativeRange", {{"type", "spot"}, {"range", -1}}, {"light 0", "range (-1"}},
        {"ColorOfTwo", {{"type", "point"}, {"color", {1, 1}}}, {"light 0", "'color'"}},
        {"InnerNotBelowOuter",
         {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}},
         {"light 0 spot has invalid cone angles (innerConeAngle 0.5, outerConeAngle 0.5"}},
        {"OuterPastHalfPi",
         {{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}},
         {"light 0 spot", "outerConeAngle 2"}},
        {"NegativeInner",
         {{"type", "spot"}, {"spot", {{"innerConeAngle", -0.1}}}},
         {"light 0 spot", "innerConeAngle -0.1"}},
        {"InnerPastDefaultOuter",
         {{"type", "spot"}, {"spot", {{"innerConeAngle", 1.0}}}},
         {"light 0 spot", "innerConeAngle 1, outerConeAngle 0.785398"}},
        {"SpotNotAnObject", {{"type", "spot"}, {"spot", 1}}, {"light 0", "'spot'"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        auto builder = lightsBuilder(json::array({c.light}));
        const auto result = loadGltf(builder);
        ASSERT_FALSE(result.ok());
        EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat);
        for (const std::string& fragment : c.fragments) {
            EXPECT_NE(result.error().message.find(fragment), std::string::npos)
                << "missing '" << fragment << "' in: " << result.error().message;
        }
    }
}

TEST(LightsCamerasTest, LightsNotAnArrayIsAnError) {
    auto builder = lightsBuilder(json::object());
    expectError(loadGltf(builder), ErrorCode::InvalidFormat, {"KHR_lights_punctual", "'lights'"});
}

TEST(LightsCamerasTest, BadLightIndexNamesTheNode) {
    auto builder = lightsBuilder(json::array({{{"type", "point"}}}));
    placeLight(builder, 0, 4);
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"test.gltf: node 0 refers to light 4", "the asset has 1 light."});

    auto noLights = triangleBuilder();
    placeLight(noLights, 0, 0);
    expectError(loadGltf(noLights), ErrorCode::InvalidFormat,
                {"node 0 refers to light 0", "the asset has 0 lights."});

    auto notAnIndex = lightsBuilder(json::array({{{"type", "point"}}}));
    notAnIndex.json()["nodes"][0]["extensions"]["KHR_lights_punctual"] = {{"light", "sun"}};
    expectError(loadGltf(notAnIndex), ErrorCode::InvalidFormat,
                {"node 0 KHR_lights_punctual", "'light'"});
}

TEST(LightsCamerasTest, CamerasParse) {
    auto builder = triangleBuilder();
    builder.json()["cameras"] = json::array({
        {{"type", "perspective"},
         {"name", "wide"},
         {"perspective", {{"yfov", 1.0}, {"aspectRatio", 1.5}, {"znear", 0.1}, {"zfar", 100.0}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.25}}}},
        {{"type", "orthographic"},
         {"orthographic", {{"xmag", 2.0}, {"ymag", -3.0}, {"znear", 0.0}, {"zfar", 50.0}}}},
    });
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->cameras.size(), 3u);
    const auto& cameras = scene->cameras;
    EXPECT_EQ(cameras[0].name, "wide");
    EXPECT_EQ(cameras[0].projection, CameraProjection::Perspective);
    EXPECT_EQ(cameras[0].yfov, 1.0f);
    EXPECT_EQ(cameras[0].aspectRatio, 1.5f);
    EXPECT_EQ(cameras[0].znear, 0.1f);
    EXPECT_EQ(cameras[0].zfar, 100.0f);
    EXPECT_EQ(cameras[1].yfov, 0.5f);
    EXPECT_EQ(cameras[1].aspectRatio, 0.0f);  // Absent: the target's aspect.
    EXPECT_EQ(cameras[1].znear, 0.25f);
    EXPECT_EQ(cameras[1].zfar, 0.0f);  // Absent: infinite.
    EXPECT_EQ(cameras[2].projection, CameraProjection::Orthographic);
    EXPECT_EQ(cameras[2].xmag, 2.0f);
    EXPECT_EQ(cameras[2].ymag, -3.0f);  // Nonzero is all the specification asks.
    EXPECT_EQ(cameras[2].znear, 0.0f);
    EXPECT_EQ(cameras[2].zfar, 50.0f);
    EXPECT_TRUE(scene->cameraInstances.empty());
}

TEST(LightsCamerasTest, InvalidCamerasAreErrors) {
    struct Case {
        const char* name;
        json camera;
        std::vector<std::string> fragments;
    };
    auto perspective = [](json values) {
        return json{{"type", "perspective"}, {"perspective", values}};
    };
    auto orthographic = [](json values) {
        return json{{"type", "orthographic"}, {"orthographic", values}};
    };
    const std::vector<Case> cases = {
        {"UnknownType", {{"type", "fisheye"}}, {"camera 0 has an unknown type ('fisheye'"}},
        {"MissingType", json::object(), {"camera 0 lacks the required 'type'"}},
        {"NoPerspectiveObject",
         {{"type", "perspective"}},
         {"camera 0 has type 'perspective' but no 'perspective' object"}},
        {"NoOrthographicObject",
         {{"type", "orthographic"}, {"perspective", {{"yfov", 1}, {"znear", 1}}}},
         {"camera 0 has type 'orthographic' but no 'orthographic' object"}},
        {"ZeroYfov",
         perspective({{"yfov", 0}, {"znear", 0.1}}),
         {"camera 0 perspective has an invalid yfov (0"}},
        {"MissingYfov",
         perspective({{"znear", 0.1}}),
         {"camera 0 perspective lacks the required 'yfov'"}},
        {"ZeroZnear",
         perspective({{"yfov", 1}, {"znear", 0}}),
         {"camera 0 perspective has an invalid znear (0"}},
        {"MissingZnear", perspective({{"yfov", 1}}), {"camera 0 perspective", "'znear'"}},
        {"ZfarNotPastZnear",
         perspective({{"yfov", 1}, {"znear", 1}, {"zfar", 0.5}}),
         {"camera 0 perspective has an invalid zfar (0.5", "znear (1)"}},
        {"ZeroAspect",
         perspective({{"yfov", 1}, {"znear", 1}, {"aspectRatio", 0}}),
         {"camera 0 perspective has an invalid aspectRatio (0"}},
        {"YfovString",
         perspective({{"yfov", "wide"}, {"znear", 1}}),
         {"camera 0 perspective", "'yfov'"}},
        {"ZeroXmag",
         orthographic({{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}),
         {"camera 0 orthographic has an invalid xmag (0"}},
        {"ZeroYmag",
         orthographic({{"xmag", 1}, {"ymag", 0}, {"znear", 0}, {"zfar", 1}}),
         {"camera 0 orthographic has an invalid ymag (0"}},
        {"NegativeOrthoZnear",
         orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", -1}, {"zfar", 1}}),
         {"camera 0 orthographic has an invalid znear (-1"}},
        {"OrthoZfarAtZnear",
         orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 2}}),
         {"camera 0 orthographic has an invalid zfar (2", "znear (2)"}},
        {"OrthoMissingZfar",
         orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 0}}),
         {"camera 0 orthographic lacks the required 'zfar'"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        auto builder = triangleBuilder();
        builder.json()["cameras"] = json::array({c.camera});
        const auto result = loadGltf(builder);
        ASSERT_FALSE(result.ok());
        EXPECT_EQ(result.error().code, ErrorCode::InvalidFormat);
        EXPECT_EQ(result.error().message.rfind("test.gltf: ", 0), 0u) << result.error().message;
        for (const std::string& fragment : c.fragments) {
            EXPECT_NE(result.error().message.find(fragment), std::string::npos)
                << "missing '" << fragment << "' in: " << result.error().message;
        }
    }
}

TEST(LightsCamerasTest, CamerasArePlacedWithoutScale) {
    auto builder = triangleBuilder();
    builder.json()["cameras"] =
        json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}}}},
                     {{"type", "orthographic"},
                      {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}}}});
    const glm::quat turn = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    const glm::quat tilt = glm::angleAxis(-0.4f, glm::vec3(1, 0, 0));
    const auto child = builder.addNode({.translation = glm::vec3(0, 1, 0), .rotation = tilt});
    const auto parent = builder.addNode({.children = {child},
                                         .translation = glm::vec3(4, 5, 6),
                                         .rotation = turn,
                                         .scale = glm::vec3(2, 3, 0.5f)});
    builder.json()["nodes"][child]["camera"] = 1;
    builder.json()["nodes"][parent]["camera"] = 0;
    builder.json()["scenes"][0]["nodes"] = {0, parent};
    auto scene = loadGltf(builder);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->cameraInstances.size(), 2u);

    // Depth-first: the parent's camera comes first. Its scale is dropped, rotation and
    // translation kept exactly.
    const CameraInstance& first = scene->cameraInstances[0];
    EXPECT_EQ(first.camera.value, 0u);
    EXPECT_EQ(first.node.value, parent);
    glm::mat4 expected = glm::translate(glm::mat4(1.0f), glm::vec3(4, 5, 6)) * glm::mat4_cast(turn);
    expectNear(first.world, expected);

    // The child sits under a non-uniformly scaled parent, so its world matrix has shear; the
    // camera keeps the world position and the world view direction (-Z) and gets an
    // orthonormal, right-handed frame.
    const CameraInstance& second = scene->cameraInstances[1];
    EXPECT_EQ(second.camera.value, 1u);
    EXPECT_EQ(second.node.value, child);
    const glm::mat4& world = scene->nodes[child].world;
    expectNear(glm::vec3(second.world[3]), glm::vec3(world[3]));
    expectNear(glm::vec3(second.world[2]), glm::normalize(glm::vec3(world[2])));
    const glm::mat3 rotation(second.world);
    expectNear(glm::mat4(glm::transpose(rotation) * rotation), glm::mat4(1.0f));
    EXPECT_NEAR(glm::determinant(rotation), 1.0f, 1e-5f);
    EXPECT_EQ(second.world[0][3], 0.0f);
    EXPECT_EQ(second.world[3][3], 1.0f);
}

TEST(LightsCamerasTest, BadCameraIndexNamesTheNode) {
    auto builder = triangleBuilder();
    builder.json()["cameras"] =
        json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}}}}});
    builder.json()["nodes"][0]["camera"] = 3;
    expectError(loadGltf(builder), ErrorCode::InvalidFormat,
                {"test.gltf: node 0 refers to camera 3", "the asset has 1 camera."});
}

TEST(LightsCamerasTest, SampleModelCameras) {
    const auto dir = test::sharedModelsDir();
    if (!dir) {
        GTEST_SKIP() << "The shared sample models (../shared/models) are absent; skipping.";
    }
    struct Expected {
        const char* file;
        float yfov;
        float aspectRatio;
        float znear;
        float zfar;
    };
    for (const Expected& model :
         {Expected{"Duck/glTF/Duck.gltf", 0.6605925559997559f, 1.5f, 1.0f, 10000.0f},
          Expected{"2CylinderEngine/glTF-Binary/2CylinderEngine.glb", 0.3143463730812073f, 1.0f,
                   0.04999999701976776f, 1000000.0f}}) {
        SCOPED_TRACE(model.file);
        auto scene = loadScene(*dir / model.file, {.decodeImages = false});
        ASSERT_TRUE(scene.ok()) << scene.error().message;
        ASSERT_EQ(scene->cameras.size(), 1u);
        const CameraData& camera = scene->cameras[0];
        EXPECT_EQ(camera.projection, CameraProjection::Perspective);
        EXPECT_FLOAT_EQ(camera.yfov, model.yfov);
        EXPECT_FLOAT_EQ(camera.aspectRatio, model.aspectRatio);
        EXPECT_FLOAT_EQ(camera.znear, model.znear);
        EXPECT_FLOAT_EQ(camera.zfar, model.zfar);
        ASSERT_EQ(scene->cameraInstances.size(), 1u);
        const CameraInstance& placed = scene->cameraInstances[0];
        EXPECT_EQ(placed.camera.value, 0u);
        // The camera stands where its node does and looks along the node's world -Z.
        const glm::mat4& world = scene->nodes[placed.node.index()].world;
        expectNear(glm::vec3(placed.world[3]), glm::vec3(world[3]), 1e-3f);
        expectNear(glm::vec3(placed.world[2]), glm::normalize(glm::vec3(world[2])));
        EXPECT_TRUE(scene->lights.empty());
        EXPECT_TRUE(scene->lightInstances.empty());
    }
}

}  // namespace
}  // namespace encore::scene
