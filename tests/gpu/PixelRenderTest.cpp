// Exact pixel checks on tiny in-code scenes, for every strategy: a lit triangle's colour at known
// pixels, depth order of two quads regardless of draw order, u8 indices and generated normals.
// Strategies before `materials` shade with one directional light; the materials strategies are
// rendered with the shading-normal debug channel, whose colour these scenes predict exactly.

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;

// The lighting of lighting.wgsl for a white surface.
double litWhite(const glm::vec3& normal) {
    const glm::vec3 light = glm::normalize(glm::vec3(0.25f, 0.5f, 1.0f));
    return 0.1 + std::max(0.0f, glm::dot(glm::normalize(normal), light));
}

test::Rgba gray(double linear) {
    const std::uint8_t value = test::linearToSrgb8(linear);
    return {value, value, value, 255};
}

// The renderer's clear colour (0.05, 0.05, 0.06) encoded to sRGB.
test::Rgba background() {
    return {test::linearToSrgb8(0.05), test::linearToSrgb8(0.05), test::linearToSrgb8(0.06), 255};
}

using test::frontCamera;

class PixelRenderTest : public ::testing::TestWithParam<StrategyKind> {
  protected:
    // Loads the builder's asset and renders it from the front camera.
    image::ImageRgba8 render(const test::GltfBuilder& builder) {
        gpu::Context* context = test::vulkanContext();
        EXPECT_NE(context, nullptr);
        if (!context) {
            return {};
        }
        auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "pixels.glb");
        EXPECT_TRUE(scene.ok()) << scene.error().message;
        if (!scene) {
            return {};
        }
        mScene = std::move(*scene);
        auto renderer = Renderer::create(
            *context, test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Normal));
        EXPECT_TRUE(renderer.ok()) << renderer.error().message;
        auto prepared = renderer->prepare(mScene, GetParam());
        EXPECT_TRUE(prepared.ok()) << prepared.error().message;
        renderer->renderFrame(frontCamera());
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok()) << image.error().message;
        EXPECT_TRUE(context->checkNoErrors("rendering").ok());
        return image.ok() ? std::move(*image) : image::ImageRgba8{};
    }

    // A white surface with this normal, as the strategy under test draws it.
    test::Rgba lit(const glm::vec3& normal) const {
        if (!test::shadesMaterials(GetParam())) {
            return gray(litWhite(normal));
        }
        const glm::vec3 encoded = glm::normalize(normal) * 0.5f + 0.5f;
        return {test::linearToSrgb8(encoded.x), test::linearToSrgb8(encoded.y),
                test::linearToSrgb8(encoded.z), 255};
    }

    void expectPixel(const image::ImageRgba8& image,
                     const glm::vec3& point,
                     const test::Rgba& expected,
                     const char* what) {
        ASSERT_EQ(image.width, kSize);
        const auto [x, y] = test::pixelOf(frontCamera(), point, kSize, kSize);
        const test::Rgba actual = test::pixelAt(image, x, y);
        EXPECT_LE(test::channelDistance(actual, expected), 1)
            << what << " at pixel (" << x << ", " << y << "): " << test::describe(actual)
            << ", expected " << test::describe(expected);
    }

    scene::SceneData mScene;
};

std::uint32_t addTriangle(test::GltfBuilder& builder, bool withNormals) {
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}});
    if (withNormals) {
        primitive.attributes["NORMAL"] = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    }
    return builder.addMesh(primitive);
}

TEST_P(PixelRenderTest, TriangleHasTheLitColourInsideAndBackgroundOutside) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    builder.addScene({builder.addNode({.mesh = addTriangle(builder, true)})});
    const auto image = render(builder);
    expectPixel(image, {0.0f, 0.0f, 0.0f}, lit({0, 0, 1}), "triangle centre");
    expectPixel(image, {0.0f, -0.8f, 0.0f}, lit({0, 0, 1}), "near the base");
    expectPixel(image, {0.9f, 0.9f, 0.0f}, background(), "outside, right of the apex");
    expectPixel(image, {-1.2f, 0.0f, 0.0f}, background(), "outside, left");
    expectPixel(image, {0.0f, -1.3f, 0.0f}, background(), "outside, below the base");
}

TEST_P(PixelRenderTest, MissingNormalsAreGeneratedFlat) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    builder.addScene({builder.addNode({.mesh = addTriangle(builder, false)})});
    const auto image = render(builder);
    // Counter-clockwise seen from +Z: the flat normal faces the camera.
    expectPixel(image, {0.0f, 0.0f, 0.0f}, lit({0, 0, 1}), "triangle centre");
}

TEST_P(PixelRenderTest, EightBitIndicesAreWidened) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] =
        builder.addPositions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
    primitive.attributes["NORMAL"] =
        builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    primitive.indices = builder.addIndices<std::uint8_t>({0, 1, 2, 0, 2, 3});
    builder.addScene({builder.addNode({.mesh = builder.addMesh(primitive)})});
    const auto image = render(builder);
    expectPixel(image, {0.5f, 0.5f, 0.0f}, lit({0, 0, 1}), "upper triangle");
    expectPixel(image, {-0.5f, -0.5f, 0.0f}, lit({0, 0, 1}), "lower triangle");
    expectPixel(image, {0.0f, 1.3f, 0.0f}, background(), "above the quad");
}

// A quad in the plane z = depth, spanning [left, right] x [-1, 1], with one normal.
std::uint32_t addQuad(test::GltfBuilder& builder,
                      float left,
                      float right,
                      float depth,
                      const glm::vec3& normal) {
    test::GltfBuilder::PrimitiveDesc primitive;
    primitive.attributes["POSITION"] = builder.addPositions(
        {{left, -1, depth}, {right, -1, depth}, {right, 1, depth}, {left, 1, depth}});
    primitive.attributes["NORMAL"] = builder.addNormals({normal, normal, normal, normal});
    primitive.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    return builder.addMesh(primitive);
}

TEST_P(PixelRenderTest, NearerQuadWinsWhateverTheDrawOrder) {
    ENCORE_REQUIRE_VULKAN(context);
    const glm::vec3 facing(0, 0, 1);
    const glm::vec3 downward(0, -1, 0);  // Lit by the ambient term only.
    for (bool nearFirst : {true, false}) {
        SCOPED_TRACE(nearFirst ? "near quad drawn first" : "far quad drawn first");
        test::GltfBuilder builder;
        const auto nearQuad =
            builder.addNode({.mesh = addQuad(builder, -1.0f, 0.5f, 0.5f, facing)});
        const auto farQuad =
            builder.addNode({.mesh = addQuad(builder, -0.5f, 1.0f, -0.5f, downward)});
        builder.addScene(nearFirst ? std::vector{nearQuad, farQuad}
                                   : std::vector{farQuad, nearQuad});
        const auto image = render(builder);
        expectPixel(image, {0.0f, 0.0f, 0.5f}, lit(facing), "overlap: near quad");
        expectPixel(image, {-0.8f, 0.0f, 0.5f}, lit(facing), "near quad only");
        expectPixel(image, {0.9f, 0.0f, -0.5f}, lit(downward), "far quad only");
    }
}

INSTANTIATE_TEST_SUITE_P(AllStrategies,
                         PixelRenderTest,
                         ::testing::ValuesIn(allStrategies()),
                         [](const auto& info) { return test::strategyTestName(info.param); });

}  // namespace
}  // namespace encore::render
