// KHR_lights_punctual as the extension specifies it, on a white rough plane with image-based
// lighting off: inverse-square falloff, the smooth range window, the spot cone, directional
// lights independent of position, and lights placed and turned by their nodes.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

struct LightDesc {
    std::string type = "point";
    float intensity = 10.0f;
    std::optional<float> range;
    float innerCone = 0.0f;
    float outerCone = glm::quarter_pi<float>();
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // Lights shine along the node's -Z.
};

// A 4x4 white, fully rough dielectric plane at z = 0 facing +Z, and one light.
scene::SceneData litPlane(const LightDesc& light) {
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc plane = builder.addFacingQuad({-2, -2}, {2, 2});
    plane.material = builder.addMaterial({.baseColor = glm::vec4(1.0f), .roughness = 1.0f});
    const std::uint32_t planeNode = builder.addNode({.mesh = builder.addMesh(plane)});
    nlohmann::json lightJson = {{"type", light.type}, {"intensity", light.intensity}};
    if (light.range) {
        lightJson["range"] = *light.range;
    }
    if (light.type == "spot") {
        lightJson["spot"] = {{"innerConeAngle", light.innerCone},
                             {"outerConeAngle", light.outerCone}};
    }
    auto& json = builder.json();
    json["extensionsUsed"] = {"KHR_lights_punctual"};
    json["extensions"]["KHR_lights_punctual"]["lights"] = {lightJson};
    const std::uint32_t lightNode =
        builder.addNode({.translation = light.position, .rotation = light.rotation});
    json["nodes"][lightNode]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
    builder.addScene({planeNode, lightNode});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "light.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

// HDR red channel at the plane points, seen from straight above.
std::vector<float> radianceAt(const LightDesc& light, const std::vector<glm::vec3>& points) {
    gpu::Context* context = test::vulkanContext();
    const scene::SceneData scene = litPlane(light);
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.target.hdr = true;  // Reads the linear colour back.
    options.lighting.imageBasedLighting = false;
    auto renderer = Renderer::create(*context, options);
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    const Camera camera =
        Camera::lookAt({0, 0, 3}, {0, 0, 0}, glm::radians(80.0f), 1.0f, 0.1f, 10.0f);
    renderer->renderFrame(camera);
    auto hdr = renderer->readHdrImage();
    EXPECT_TRUE(hdr.ok());
    EXPECT_TRUE(context->checkNoErrors("punctual lights").ok());
    std::vector<float> values;
    for (const glm::vec3& point : points) {
        const auto [x, y] = test::pixelOf(camera, point, kSize, kSize);
        values.push_back(hdr.ok() ? (*hdr)[(std::size_t(y) * kSize + x) * 4] : -1.0f);
    }
    return values;
}

TEST(PunctualLightTest, PointLightsFallOffWithTheInverseSquare) {
    ENCORE_REQUIRE_VULKAN(context);
    const float near = radianceAt({.position = {0, 0, 1}}, {{0, 0, 0}})[0];
    const float far = radianceAt({.position = {0, 0, 2}}, {{0, 0, 0}})[0];
    // Light and view both straight above the centre: only the distance changes.
    ASSERT_GT(far, 0.01f);
    EXPECT_NEAR(near / far, 4.0f, 0.04f);
    // Lambertian plus a little rough specular: intensity 10 at 1 m gives about 10 / pi.
    EXPECT_NEAR(near, 10.0f / glm::pi<float>(), 0.6f);
}

TEST(PunctualLightTest, RangeEndsTheLightSmoothly) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::vector<glm::vec3> points = {{0, 0, 0}, {1.6f, 0, 0}};
    const auto unlimited = radianceAt({.position = {0, 0, 1}}, points);
    const auto limited = radianceAt({.range = 1.5f, .position = {0, 0, 1}}, points);
    // (1 - (d / range)^4) at d = 1, and nothing past the range (d = 1.89 at the second point).
    EXPECT_NEAR(limited[0] / unlimited[0], 1.0f - std::pow(1.0f / 1.5f, 4.0f), 0.02f);
    EXPECT_GT(unlimited[1], 0.05f);
    EXPECT_EQ(limited[1], 0.0f);
}

TEST(PunctualLightTest, SpotLightsLightOnlyInsideTheirCone) {
    ENCORE_REQUIRE_VULKAN(context);
    // A spot at 1 m pointing down -Z: inside 0.3 rad full, outside 0.5 rad nothing.
    const std::vector<glm::vec3> points = {{0, 0, 0}, {0.2f, 0, 0}, {0.8f, 0, 0}};
    const auto spot = radianceAt(
        {.type = "spot", .innerCone = 0.3f, .outerCone = 0.5f, .position = {0, 0, 1}}, points);
    const auto point = radianceAt({.position = {0, 0, 1}}, points);
    EXPECT_NEAR(spot[0], point[0], 0.01f * point[0]);  // atan(0) = 0 < inner.
    EXPECT_NEAR(spot[1], point[1], 0.01f * point[1]);  // atan(0.2) = 0.197 < inner.
    EXPECT_EQ(spot[2], 0.0f);                          // atan(0.8) = 0.67 > outer.
    EXPECT_GT(point[2], 0.05f);
}

TEST(PunctualLightTest, DirectionalLightsIgnorePositionAndFollowTheNodeRotation) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::vector<glm::vec3> points = {{0, 0, 0}, {1.5f, 1.5f, 0}};
    // Straight down: the same everywhere and wherever the node is; E = 10 lux gives 10 / pi.
    const auto down = radianceAt({.type = "directional", .position = {5, 5, 9}}, points);
    EXPECT_NEAR(down[0], down[1], 0.02f * down[0]);
    EXPECT_NEAR(down[0], 10.0f / glm::pi<float>(), 0.6f);
    // Turned 60 degrees about +X: cos 60 of the light arrives.
    const glm::quat tilt = glm::angleAxis(glm::radians(60.0f), glm::vec3(1, 0, 0));
    const auto tilted =
        radianceAt({.type = "directional", .position = {0, 0, 1}, .rotation = tilt}, points);
    EXPECT_NEAR(tilted[0] / down[0], 0.5f, 0.05f);
}

}  // namespace
}  // namespace encore::render
