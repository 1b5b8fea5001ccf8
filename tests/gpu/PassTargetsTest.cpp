// Pass targets (RendererOptions::passTargets, render/PassTargets.h): the pass images drawn in the
// colour frame's render pass hold exactly what the debug channels' frames hold, and a renderer
// without them draws as it always did (one colour target, the same pipelines, no variant).

#include <gtest/gtest.h>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/render/Renderer.h"
#include "gpu/Readback.h"
#include "render/PipelineKey.h"
#include "render/RenderSetup.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 48;

// An opaque quad and a blended one in front of it, half over it, half over nothing: blending
// and coverage meet the passes.
std::vector<std::uint8_t> overlappingQuads() {
    test::GltfBuilder builder;
    std::vector<std::uint32_t> nodes;
    struct Quad {
        float left, right, z;
        glm::vec4 color;
        const char* alphaMode;
    };
    for (const Quad& quad : {Quad{-1.0f, 0.3f, 0.0f, {0.8f, 0.3f, 0.1f, 1.0f}, "OPAQUE"},
                             Quad{-0.2f, 1.0f, 0.4f, {0.1f, 0.5f, 0.9f, 0.5f}, "BLEND"}}) {
        const auto positions = builder.addPositions({{quad.left, -0.6f, quad.z},
                                                     {quad.right, -0.5f, quad.z},
                                                     {quad.right, 0.5f, quad.z},
                                                     {quad.left, 0.6f, quad.z}});
        const auto normals = builder.addNormals(
            std::vector<glm::vec3>(4, glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f))));
        const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
        const auto material = builder.addMaterial({.baseColor = quad.color,
                                                   .metallic = 0.3f,
                                                   .roughness = 0.7f,
                                                   .alphaMode = quad.alphaMode});
        const auto mesh =
            builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                             .indices = indices,
                             .material = material});
        nodes.push_back(builder.addNode({.mesh = mesh}));
    }
    builder.addScene(nodes);
    return builder.toGlb();
}

struct Frames {
    image::ImageRgba8 color;
    std::vector<image::ImageRgba8> rgba;  // Normal, albedo, material.
    std::vector<float> depth;             // Red channel of the depth channel's HDR frame.
    std::vector<float> ids;               // The node id as the segmentation channel writes it.
    std::uint64_t pipelines = 0;
};

RendererOptions optionsFor(std::uint32_t samples, PassTargets targets) {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, samples, DebugChannel::Shaded);
    options.target.hdr = true;
    options.toneMapping.background = BackgroundKind::Transparent;
    options.passTargets = targets;
    return options;
}

const Camera kCamera = Camera::lookAt({0.3f, 0.2f, 3.0f}, {0, 0, 0}, 0.8f, 1.0f, 0.1f, 10.0f);

TEST(PassTargetsTest, PassImagesEqualTheDebugChannelsFrames) {
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadSceneFromMemory(overlappingQuads(), {}, "quads.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (const std::uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE("samples " + std::to_string(samples));
        // One frame per pass through the debug channels, tone mapping off.
        auto frames = Renderer::create(*context, optionsFor(samples, PassTargets::None));
        ASSERT_TRUE(frames.ok()) << frames.error().message;
        ASSERT_TRUE(frames->prepare(*scene, StrategyKind::Bundles).ok());
        EXPECT_FALSE(frames->passTexture(PassImage::Normal));
        EXPECT_EQ(internals(*frames).setup().passTargets, 0);
        frames->renderFrame(kCamera);
        auto color = frames->readImage();
        ASSERT_TRUE(color.ok());
        ToneMappingOptions identity = frames->toneMapping();
        identity.toneMapping = ToneMapping::None;
        identity.exposure = 1.0f;
        ASSERT_TRUE(frames->setToneMapping(identity).ok());
        const auto channel = [&](DebugChannel debug) {
            LightingParameters lighting = frames->lighting();
            lighting.debugChannel = debug;
            frames->setLighting(lighting);
            frames->renderFrame(kCamera);
        };
        std::vector<image::ImageRgba8> debugImages;
        for (const DebugChannel debug :
             {DebugChannel::Normal, DebugChannel::BaseColor, DebugChannel::Material}) {
            channel(debug);
            auto image = frames->readImage();
            ASSERT_TRUE(image.ok());
            debugImages.push_back(std::move(*image));
        }
        channel(DebugChannel::Depth);
        auto depth = frames->readHdrImage();
        channel(DebugChannel::SegmentNode);
        auto ids = frames->readHdrImage();
        ASSERT_TRUE(depth.ok() && ids.ok());

        // The same in one frame with pass targets.
        auto targets = Renderer::create(*context, optionsFor(samples, PassTargets::SegmentByNode));
        ASSERT_TRUE(targets.ok()) << targets.error().message;
        ASSERT_TRUE(targets->prepare(*scene, StrategyKind::Bundles).ok());
        targets->renderFrame(kCamera);
        ASSERT_TRUE(context->checkNoErrors("Drawing with pass targets").ok());
        auto targetColor = targets->readImage();
        ASSERT_TRUE(targetColor.ok());
        EXPECT_TRUE(targetColor->pixels == color->pixels) << "the colour image changed";
        const PassImage images[] = {PassImage::Normal, PassImage::Albedo, PassImage::Material};
        for (std::size_t i = 0; i < 3; ++i) {
            auto image = gpu::readTexture(*context, targets->passTexture(images[i]));
            ASSERT_TRUE(image.ok());
            EXPECT_TRUE(image->pixels == debugImages[i].pixels) << "pass image " << i;
        }
        auto depthAndId =
            gpu::readTextureRgba16Float(*context, targets->passTexture(PassImage::DepthAndId));
        ASSERT_TRUE(depthAndId.ok());
        std::size_t covered = 0;
        for (std::size_t texel = 0; texel < std::size_t(kSize) * kSize; ++texel) {
            const float* packed = &(*depthAndId)[texel * 4];
            ASSERT_EQ(packed[0], (*depth)[texel * 4]) << "depth at " << texel;
            ASSERT_EQ(packed[3], (*depth)[texel * 4 + 3]) << "coverage at " << texel;
            if (samples == 1) {
                ASSERT_EQ(packed[1], (*ids)[texel * 4]) << "id % 256 at " << texel;
                ASSERT_EQ(packed[2], (*ids)[texel * 4 + 1]) << "id / 256 at " << texel;
            }
            covered += packed[3] > 0.0f;
        }
        EXPECT_GT(covered, std::size_t(kSize) * kSize / 4) << "the quads were drawn";
        // Variants, not more pipelines: each pipeline gains the targets.
        EXPECT_EQ(internals(*targets).setup().pipelinesCreated,
                  internals(*frames).setup().pipelinesCreated);
    }
}

// Only the variant with pass targets has them: the flags without it, and its pipelines' colour
// targets, are what they were.
TEST(PassTargetsTest, OnlyThePassTargetVariantHasMoreColourTargets) {
    shaders::ShaderVariantKey key;
    key.materials = true;
    EXPECT_EQ(sceneColorTargets(key), 1u);
    EXPECT_EQ(key.flags().count("PASS_TARGETS"), 0u);
    key.passTargets = 2;
    EXPECT_EQ(sceneColorTargets(key), 5u);
    EXPECT_EQ(key.flags().count("PASS_TARGETS"), 1u);
    EXPECT_EQ(key.flags().count("SEGMENT_BY_MESH"), 1u);
    key.materials = false;  // Vertex colours: no pass images to write.
    EXPECT_EQ(sceneColorTargets(key), 1u);
    EXPECT_EQ(key.flags().count("PASS_TARGETS"), 0u);
}

TEST(PassTargetsTest, StrategiesWithoutMaterialShadersAreRefused) {
    ENCORE_REQUIRE_VULKAN(context);
    auto scene = scene::loadSceneFromMemory(overlappingQuads(), {}, "quads.glb");
    ASSERT_TRUE(scene.ok());
    auto renderer = Renderer::create(*context, optionsFor(1, PassTargets::SegmentByMesh));
    ASSERT_TRUE(renderer.ok());
    auto prepared = renderer->prepare(*scene, StrategyKind::Naive);
    ASSERT_FALSE(prepared.ok());
    EXPECT_NE(prepared.error().message.find("Pass targets need a strategy"), std::string::npos)
        << prepared.error().message;
}

}  // namespace
}  // namespace encore::render
