// Pixel checks of the `materials` strategy on tiny in-code scenes: base colour factors, sRGB
// textures, vertex colours, MASK (a cutoff of 0 stays 0), BLEND sorted back to front,
// double-sided culling and the glTF default material. Each covers a gap of the case study's code.

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TextureFixtures.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
const glm::vec3 kFacing(0.0f, 0.0f, 1.0f);

// These scenes render with the base-colour debug channel and no tone mapping
// (test::pixelTestOptions): a material's pixels are its base colour (factor x texture x vertex
// colour), independent of the light, so every expectation below is exact. The lit result is
// checked by ShadingPhysicsTest and the reference comparison.
double lighting(const glm::vec3&) {
    return 1.0;
}

const glm::dvec3 kBackground(0.05, 0.05, 0.06);

test::Rgba encode(const glm::dvec3& linear) {
    return {test::linearToSrgb8(linear.r), test::linearToSrgb8(linear.g),
            test::linearToSrgb8(linear.b), 255};
}

using test::frontCamera;

struct QuadDesc {
    float left = -1.0f;
    float right = 1.0f;
    float depth = 0.0f;
    std::optional<std::uint32_t> material;
    bool clockwise = false;  // Faces away from the camera when true.
    bool texcoords = false;
    std::optional<glm::vec4> color;
};

std::uint32_t addQuad(test::GltfBuilder& builder, const QuadDesc& quad) {
    test::GltfBuilder::PrimitiveDesc primitive;
    const float d = quad.depth;
    primitive.attributes["POSITION"] = builder.addPositions(
        {{quad.left, -1, d}, {quad.right, -1, d}, {quad.right, 1, d}, {quad.left, 1, d}});
    primitive.attributes["NORMAL"] = builder.addNormals({kFacing, kFacing, kFacing, kFacing});
    if (quad.texcoords) {
        primitive.attributes["TEXCOORD_0"] = builder.addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    }
    if (quad.color) {
        primitive.attributes["COLOR_0"] =
            builder.addColors({*quad.color, *quad.color, *quad.color, *quad.color});
    }
    primitive.indices = quad.clockwise ? builder.addIndices<std::uint16_t>({0, 2, 1, 0, 3, 2})
                                       : builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    primitive.material = quad.material;
    return builder.addNode({.mesh = builder.addMesh(primitive)});
}

// A 1x1 PNG embedded through a bufferView; returns the texture index.
std::uint32_t addPixelTexture(test::GltfBuilder& builder, std::array<std::uint8_t, 4> rgba) {
    image::ImageRgba8 pixel{1, 1, {rgba.begin(), rgba.end()}};
    const auto png = image::encodePng(pixel);
    EXPECT_TRUE(png.ok());
    const std::uint32_t view = builder.addBufferView(*png);
    auto& json = builder.json();
    json["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
    json["textures"].push_back({{"source", json["images"].size() - 1}});
    return static_cast<std::uint32_t>(json["textures"].size() - 1);
}

class MaterialPixelTest : public ::testing::Test {
  protected:
    image::ImageRgba8 render(test::GltfBuilder& builder, const std::vector<std::uint32_t>& nodes) {
        builder.addScene(nodes);
        gpu::Context* context = test::vulkanContext();
        if (!context) {
            ADD_FAILURE() << "no Vulkan context";
            return {};
        }
        auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "materials.glb");
        EXPECT_TRUE(scene.ok()) << scene.error().message;
        if (!scene) {
            return {};
        }
        mScene = std::move(*scene);
        auto renderer = Renderer::create(*context, test::pixelTestOptions(kSize, kSize));
        EXPECT_TRUE(renderer.ok());
        auto prepared = renderer->prepare(mScene, StrategyKind::Materials);
        EXPECT_TRUE(prepared.ok()) << prepared.error().message;
        renderer->renderFrame(frontCamera());
        auto image = renderer->readImage();
        EXPECT_TRUE(image.ok()) << image.error().message;
        EXPECT_TRUE(context->checkNoErrors("materials").ok());
        return image.ok() ? std::move(*image) : image::ImageRgba8{};
    }

    void expectPixel(const image::ImageRgba8& image,
                     const glm::vec3& point,
                     const test::Rgba& expected,
                     const char* what,
                     int tolerance = 1) {
        ASSERT_EQ(image.width, kSize);
        const auto [x, y] = test::pixelOf(frontCamera(), point, kSize, kSize);
        const test::Rgba actual = test::pixelAt(image, x, y);
        EXPECT_LE(test::channelDistance(actual, expected), tolerance)
            << what << " at (" << x << ", " << y << "): " << test::describe(actual) << ", expected "
            << test::describe(expected);
    }

    scene::SceneData mScene;
};

TEST_F(MaterialPixelTest, BaseColourFactorTintsTheLighting) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const auto red = builder.addMaterial({.baseColor = {1.0f, 0.25f, 0.0f, 1.0f}});
    const auto image = render(builder, {addQuad(builder, {.material = red})});
    const double light = lighting(kFacing);
    expectPixel(image, {0, 0, 0}, encode({light, 0.25 * light, 0.0}), "red quad");
}

TEST_F(MaterialPixelTest, BaseColourTexturesAreSampledAsSrgb) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    test::GltfBuilder::MaterialDesc desc;
    desc.baseColorTexture = addPixelTexture(builder, {188, 188, 188, 255});
    const auto material = builder.addMaterial(desc);
    const auto image =
        render(builder, {addQuad(builder, {.material = material, .texcoords = true})});
    // sRGB 188 is linear 0.5; sampled as linear data it would be 0.737.
    const double expected = 0.5 * lighting(kFacing);
    expectPixel(image, {0, 0, 0}, encode(glm::dvec3(expected)), "textured quad", 2);
}

// EXT_texture_webp: the WebP image (generated here with libwebp, lossless) is drawn, not the
// fallback PNG beside it.
TEST_F(MaterialPixelTest, WebpTexturesAreDrawnInsteadOfTheirFallback) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const std::uint32_t png = test::addEmbeddedImage(
        builder, test::encodePngBytes(test::solidImage({255, 0, 0, 255})), "image/png");
    const std::uint32_t webp = test::addEmbeddedImage(
        builder, test::encodeWebpBytes(test::solidImage({188, 255, 0, 255}, 4, 4)), "image/webp");
    builder.json()["textures"].push_back(
        {{"source", png}, {"extensions", {{"EXT_texture_webp", {{"source", webp}}}}}});
    builder.json()["extensionsUsed"] = {"EXT_texture_webp"};
    test::GltfBuilder::MaterialDesc desc;
    desc.baseColorTexture = 0;
    const auto material = builder.addMaterial(desc);
    const auto image =
        render(builder, {addQuad(builder, {.material = material, .texcoords = true})});
    EXPECT_TRUE(mScene.warnings.empty());
    // sRGB 188 is linear 0.5.
    expectPixel(image, {0, 0, 0}, encode(glm::dvec3(0.5, 1.0, 0.0) * lighting(kFacing)),
                "WebP-textured quad", 2);
}

TEST_F(MaterialPixelTest, VertexColoursMultiplyTheBaseColour) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const auto image =
        render(builder, {addQuad(builder, {.color = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f)})});
    expectPixel(image, {0, 0, 0}, encode({0.0, lighting(kFacing), 0.0}), "green quad");
}

TEST_F(MaterialPixelTest, PrimitiveWithoutMaterialUsesTheDefaultMaterial) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const auto image = render(builder, {addQuad(builder, {})});
    expectPixel(image, {0, 0, 0}, encode(glm::dvec3(lighting(kFacing))), "white quad");
}

TEST_F(MaterialPixelTest, MaskDiscardsBelowTheCutoffAndKeepsACutoffOfZero) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const auto halfCut = builder.addMaterial(
        {.baseColor = {1, 1, 1, 0.4f}, .alphaMode = "MASK", .alphaCutoff = 0.5f});
    const auto zeroCut = builder.addMaterial(
        {.baseColor = {1, 1, 1, 0.4f}, .alphaMode = "MASK", .alphaCutoff = 0.0f});
    const auto image =
        render(builder, {addQuad(builder, {.left = -1.0f, .right = -0.1f, .material = halfCut}),
                         addQuad(builder, {.left = 0.1f, .right = 1.0f, .material = zeroCut})});
    expectPixel(image, {-0.5f, 0, 0}, encode(kBackground), "alpha 0.4 < cutoff 0.5: discarded");
    // A cutoff of 0 must not become the default 0.5 (the case study's `|| 0.5`).
    expectPixel(image, {0.5f, 0, 0}, encode(glm::dvec3(lighting(kFacing))),
                "alpha 0.4 >= cutoff 0: drawn");
}

TEST_F(MaterialPixelTest, SingleSidedBackFacesAreCulledDoubleSidedAreNot) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    const auto single = builder.addMaterial({});
    const auto twoSided = builder.addMaterial({.doubleSided = true});
    const auto image = render(
        builder,
        {addQuad(builder, {.left = -1.0f, .right = -0.1f, .material = single, .clockwise = true}),
         addQuad(builder, {.left = 0.1f, .right = 1.0f, .material = twoSided, .clockwise = true})});
    expectPixel(image, {-0.5f, 0, 0}, encode(kBackground), "single-sided back face");
    expectPixel(image, {0.5f, 0, 0}, encode(glm::dvec3(lighting(kFacing))),
                "double-sided back face");
}

TEST_F(MaterialPixelTest, BlendedQuadsAreDrawnBackToFrontWhateverTheNodeOrder) {
    ENCORE_REQUIRE_VULKAN(context);
    const double light = lighting(kFacing);
    // Blending happens in linear space on the sRGB target: far (blue) over the background,
    // then near (red) over that.
    const glm::dvec3 afterFar = 0.5 * glm::dvec3(0, 0, light) + 0.5 * kBackground;
    const glm::dvec3 expected = 0.5 * glm::dvec3(light, 0, 0) + 0.5 * afterFar;
    for (bool nearFirst : {true, false}) {
        SCOPED_TRACE(nearFirst ? "near node first" : "far node first");
        test::GltfBuilder builder;
        const auto red = builder.addMaterial({.baseColor = {1, 0, 0, 0.5f}, .alphaMode = "BLEND"});
        const auto blue = builder.addMaterial({.baseColor = {0, 0, 1, 0.5f}, .alphaMode = "BLEND"});
        const auto nearQuad =
            addQuad(builder, {.left = -1.0f, .right = 0.5f, .depth = 0.5f, .material = red});
        const auto farQuad =
            addQuad(builder, {.left = -0.5f, .right = 1.0f, .depth = -0.5f, .material = blue});
        const auto image = render(
            builder, nearFirst ? std::vector{nearQuad, farQuad} : std::vector{farQuad, nearQuad});
        expectPixel(image, {0.0f, 0.0f, 0.5f}, encode(expected), "overlap", 2);
    }
}

}  // namespace
}  // namespace encore::render
