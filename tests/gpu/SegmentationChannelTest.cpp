// The segmentation debug channels (DebugChannel::Segment*): each pixel says which node, mesh or
// material drew it, with every strategy that shades glTF materials in the mesh shader, and an
// instance moved after preparing keeps its ids (they ride in the normal matrix's fourth column,
// which updates leave alone).

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
constexpr std::uint32_t kLeft = 17, kRight = 47, kRow = 32;  // Inside each quad, 3 away.

// Two quads facing +Z, x from -1 to -0.2 and 0.2 to 1: nodes 0 and 1, each with its own mesh and
// material; a third material (index 0) that nothing uses shifts the material ids.
std::vector<std::uint8_t> twoQuads() {
    test::GltfBuilder builder;
    builder.addMaterial({});
    std::vector<std::uint32_t> nodes;
    for (const auto& [left, right] : {std::pair{-1.0f, -0.2f}, std::pair{0.2f, 1.0f}}) {
        const auto positions = builder.addPositions(
            {{left, -0.5f, 0.0f}, {right, -0.5f, 0.0f}, {right, 0.5f, 0.0f}, {left, 0.5f, 0.0f}});
        const auto normals = builder.addNormals(std::vector<glm::vec3>(4, {0.0f, 0.0f, 1.0f}));
        const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        const auto material = builder.addMaterial({});
        const auto mesh =
            builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                             .indices = indices,
                             .material = material});
        nodes.push_back(builder.addNode({.mesh = mesh}));
    }
    builder.addScene(nodes);
    return builder.toGlb();
}

// The id at (x, kRow) of an HDR read-back drawn through a segmentation channel.
std::uint32_t idAt(const std::vector<float>& hdr, std::uint32_t x) {
    const float* texel = &hdr[(std::size_t(kRow) * kSize + x) * 4];
    return std::uint32_t(std::lround(texel[0]) + 256 * std::lround(texel[1]));
}

TEST(SegmentationChannelTest, EveryPixelNamesTheNodeMeshOrMaterialThatDrewIt) {
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadSceneFromMemory(twoQuads(), {}, "quads.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Camera camera = Camera::lookAt({0, 0, 3}, {0, 0, 0}, 0.8f, 1.0f, 0.1f, 10.0f);
    for (const StrategyKind kind : {StrategyKind::Materials, StrategyKind::Bundles,
                                    StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
        SCOPED_TRACE(std::string(strategyName(kind)));
        RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
        options.target.hdr = true;
        auto renderer = Renderer::create(*context, options);
        ASSERT_TRUE(renderer.ok());
        ASSERT_TRUE(renderer->prepare(*scene, kind).ok());
        const auto draw = [&](DebugChannel channel) {
            LightingParameters lighting = renderer->lighting();
            lighting.debugChannel = channel;
            renderer->setLighting(lighting);
            renderer->renderFrame(camera);
            auto hdr = renderer->readHdrImage();
            EXPECT_TRUE(hdr.ok());
            return hdr.ok() ? *hdr : std::vector<float>(std::size_t(kSize) * kSize * 4);
        };
        const std::vector<float> nodes = draw(DebugChannel::SegmentNode);
        EXPECT_EQ(idAt(nodes, kLeft), 1u);
        EXPECT_EQ(idAt(nodes, kRight), 2u);
        EXPECT_EQ(idAt(nodes, kSize / 2), 0u) << "the gap between the quads";
        const std::vector<float> meshes = draw(DebugChannel::SegmentMesh);
        EXPECT_EQ(idAt(meshes, kLeft), 1u);
        EXPECT_EQ(idAt(meshes, kRight), 2u);
        const std::vector<float> materials = draw(DebugChannel::SegmentMaterial);
        EXPECT_EQ(idAt(materials, kLeft), 2u);
        EXPECT_EQ(idAt(materials, kRight), 3u);

        // The left quad moved towards the camera and up a little: still node 1.
        for (std::size_t i = 0; i < scene->instances.size(); ++i) {
            if (scene->instances[i].node.index() == 0) {
                ASSERT_TRUE(renderer
                                ->updateInstance(
                                    i, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.1f, 0.2f)))
                                .ok());
            }
        }
        const std::vector<float> moved = draw(DebugChannel::SegmentNode);
        EXPECT_EQ(idAt(moved, kLeft), 1u);
        EXPECT_EQ(idAt(moved, kRight), 2u);
        EXPECT_TRUE(context->checkNoErrors("drawing segmentation ids").ok());
    }
}

}  // namespace
}  // namespace encore::render
