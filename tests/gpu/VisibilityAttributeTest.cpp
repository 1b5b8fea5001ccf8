// The visibility passes decode vertex attributes from the geometry buffer themselves: in any
// glTF component type, aligned 32-bit floats as whole words. Here normalized integers, drawn as
// gpu-culling-bundles draws them.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "VisibilityTestSupport.h"
#include "encore/image/ImageCodec.h"

namespace encore::render {
namespace {

using test::render;

constexpr std::uint32_t kWidth = test::kVisibilityWidth;
constexpr std::uint32_t kHeight = test::kVisibilityHeight;
const Camera kFront = test::frontCamera(float(kWidth) / float(kHeight));

// Two quads whose attributes are normalized integers (KHR_mesh_quantization: 16-bit normals,
// 16-bit and 8-bit texture coordinates, 8-bit colours), which the visibility passes decode
// from the geometry buffer themselves (aligned 32-bit floats take a faster path): the base
// colour (a red and blue texture times the vertex colours) and the normals as the hardware
// reads them. The right quad samples through TEXCOORD_1, the left one has none (its fallback,
// TEXCOORD_0).
TEST(VisibilityAttributeTest, NormalizedIntegerAttributesAsTheHardwareReadsThem) {
    ENCORE_REQUIRE_VULKAN(context);
    test::GltfBuilder builder;
    auto& json = builder.json();
    json["extensionsUsed"] = {"KHR_mesh_quantization"};
    json["extensionsRequired"] = {"KHR_mesh_quantization"};
    const image::ImageRgba8 pixels{2, 1, {255, 0, 0, 255, 0, 0, 255, 255}};
    const auto png = image::encodePng(pixels);
    ASSERT_TRUE(png.ok());
    json["images"].push_back(
        {{"bufferView", builder.addBufferView(*png)}, {"mimeType", "image/png"}});
    json["samplers"].push_back({{"magFilter", 9728}, {"minFilter", 9728}});
    json["textures"].push_back({{"source", 0}, {"sampler", 0}});
    const test::GltfBuilder::AccessorOptions normalized{.normalized = true};
    std::vector<std::uint32_t> nodes;
    for (int side = 0; side < 2; ++side) {
        const float x0 = side == 0 ? -1.0f : 0.05f;
        test::GltfBuilder::PrimitiveDesc quad;
        quad.attributes["POSITION"] = builder.addPositions(
            {{x0, -0.8f, 0}, {x0 + 0.95f, -0.8f, 0}, {x0 + 0.95f, 0.8f, 0}, {x0, 0.8f, 0}});
        // Normals leaning four ways (int16, normalized: 32767 is 1).
        quad.attributes["NORMAL"] = builder.addAccessor<std::int16_t>(
            {-12000, -9000, 29000, 15000, -6000, 28000, 11000, 14000, 27000, -8000, 16000, 27500},
            "VEC3", normalized);
        const std::vector<std::uint16_t> across = {0, 0, 65535, 0, 65535, 65535, 0, 65535};
        const std::vector<std::uint8_t> acrossBytes = {0, 0, 255, 0, 255, 255, 0, 255};
        if (side == 0) {
            quad.attributes["TEXCOORD_0"] = builder.addAccessor(across, "VEC2", normalized);
        } else {
            // TEXCOORD_0 the wrong way round: only TEXCOORD_1 draws red on the left.
            quad.attributes["TEXCOORD_0"] = builder.addTexcoords({{1, 0}, {0, 0}, {0, 1}, {1, 1}});
            quad.attributes["TEXCOORD_1"] = builder.addAccessor(acrossBytes, "VEC2", normalized);
        }
        quad.attributes["COLOR_0"] = builder.addAccessor<std::uint8_t>(
            {255, 255, 255, 255, 128, 255, 64, 255, 255, 128, 255, 255, 32, 200, 255, 255}, "VEC4",
            normalized);
        quad.indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        quad.material = builder.addMaterial({.baseColorTexture = 0});
        json["materials"][side]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = side;
        nodes.push_back(builder.addNode({.mesh = builder.addMesh(quad)}));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "quantized.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (DebugChannel channel : {DebugChannel::BaseColor, DebugChannel::Normal}) {
        SCOPED_TRACE(int(channel));
        const auto expected =
            render(*context, *scene, StrategyKind::GpuCullingBundles, kFront, channel);
        const auto image = render(*context, *scene, StrategyKind::Visibility, kFront, channel);
        test::expectVisibilityClose(expected, image);
        EXPECT_GT(test::coveredFraction(image, test::pixelAt(image, 0, 0)), 0.04);
        if (channel == DebugChannel::BaseColor) {
            // Each quad is red on its left half and blue on its right, through either set.
            for (float x : {-0.75f, 0.3f}) {
                const auto [px, py] = test::pixelOf(kFront, glm::vec3(x, 0, 0), kWidth, kHeight);
                const test::Rgba left = test::pixelAt(image, px, py);
                EXPECT_GT(left[0], 100);
                EXPECT_LT(left[2], 30);
            }
        }
    }
    EXPECT_TRUE(context->checkNoErrors("visibility attributes").ok());
}

}  // namespace
}  // namespace encore::render
