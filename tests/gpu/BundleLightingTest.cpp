// A bundle recorded once stays right when lighting changes: exposure and tone mapping, the
// environment's intensity and rotation, a new environment, punctual light parameters and
// material factors all change through buffers (or in-place texture writes). Each frame after a
// change must equal a renderer created with that state from the start, and the strategy must
// not record again. Another environment object takes effect at the next prepare().

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "encore/image/HdrImage.h"
#include "encore/render/Renderer.h"
#include "render/renderer/RendererCore.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 48;

// Two spheres-worth of shading in one quad grid: a rough metal and a glossy dielectric, lit by
// the environment and one point light.
scene::SceneData litScene() {
    test::GltfBuilder builder;
    const std::uint32_t metal = builder.addMaterial(
        {.baseColor = {0.9f, 0.6f, 0.3f, 1.0f}, .metallic = 1.0f, .roughness = 0.4f});
    const std::uint32_t plastic =
        builder.addMaterial({.baseColor = {0.2f, 0.4f, 0.8f, 1.0f}, .roughness = 0.2f});
    std::vector<std::uint32_t> nodes;
    for (const auto& [material, x] : {std::pair{metal, -0.55f}, std::pair{plastic, 0.55f}}) {
        test::GltfBuilder::PrimitiveDesc quad;
        // A quad folded into a shallow roof, so normals vary across it.
        quad.attributes["POSITION"] = builder.addPositions({{-0.5f, -1, 0},
                                                            {0, -1, 0.4f},
                                                            {0.5f, -1, 0},
                                                            {-0.5f, 1, 0},
                                                            {0, 1, 0.4f},
                                                            {0.5f, 1, 0}});
        quad.indices = builder.addIndices<std::uint16_t>({0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4});
        quad.material = material;
        nodes.push_back(
            builder.addNode({.mesh = builder.addMesh(quad), .translation = glm::vec3(x, 0, 0)}));
    }
    auto& json = builder.json();
    json["extensionsUsed"] = {"KHR_lights_punctual"};
    json["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1.0, 0.9, 0.8}}, {"intensity", 6.0}}};
    test::GltfBuilder::NodeDesc lightNode{.translation = glm::vec3(0.5f, 1.0f, 2.0f)};
    const std::uint32_t light = builder.addNode(lightNode);
    json["nodes"][light]["extensions"]["KHR_lights_punctual"] = {{"light", 0}};
    nodes.push_back(light);
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "lit.glb");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : scene::SceneData{};
}

std::shared_ptr<Environment> ownEnvironment(const image::HdrImage& panorama) {
    gpu::Context* context = test::vulkanContext();
    static shaders::ShaderLibrary shaders(context->device());
    auto created = Environment::create(context->device(), context->queue(), shaders, panorama,
                                       test::testEnvironmentOptions());
    EXPECT_TRUE(created.ok());
    return std::make_shared<Environment>(std::move(*created));
}

RendererOptions shadedOptions(std::shared_ptr<Environment> environment) {
    RendererOptions options = test::pixelTestOptions(kSize, kSize, 1, DebugChannel::Shaded);
    options.toneMapping.toneMapping = ToneMapping::PbrNeutral;
    options.environment = std::move(environment);
    return options;
}

image::ImageRgba8 frame(Renderer& renderer) {
    renderer.renderFrame(test::frontCamera());
    auto image = renderer.readImage();
    EXPECT_TRUE(image.ok());
    return image.ok() ? std::move(*image) : image::ImageRgba8{};
}

// What a renderer created with `options` from the start draws.
image::ImageRgba8 freshFrame(const scene::SceneData& scene, const RendererOptions& options) {
    auto renderer = Renderer::create(*test::vulkanContext(), options);
    EXPECT_TRUE(renderer.ok());
    EXPECT_TRUE(renderer->prepare(scene, StrategyKind::Bundles).ok());
    return frame(*renderer);
}

class BundleLightingTest : public ::testing::TestWithParam<StrategyKind> {
  protected:
    void SetUp() override {
        gpu::Context* context = test::vulkanContext();
        ASSERT_NE(context, nullptr);
        mScene = litScene();
        ASSERT_EQ(mScene.lightInstances.size(), 1u);
        mEnvironment = ownEnvironment(image::makeStudioEnvironment(128));
        mOptions = shadedOptions(mEnvironment);
        auto renderer = Renderer::create(*context, mOptions);
        ASSERT_TRUE(renderer.ok());
        mRenderer = std::make_unique<Renderer>(std::move(*renderer));
        ASSERT_TRUE(mRenderer->prepare(mScene, GetParam()).ok());
        mFirst = frame(*mRenderer);
        mRecorded = internals(*mRenderer).strategy()->report().bundlesRecorded;
        ASSERT_EQ(mRecorded, test::bundlesPerRecording(GetParam()));
    }

    // The frame after a change equals a fresh renderer's and nothing was recorded again.
    void expectSameAsFresh(const RendererOptions& fresh,
                           const char* what,
                           const scene::SceneData* freshScene = nullptr) {
        const image::ImageRgba8 changed = frame(*mRenderer);
        EXPECT_GT(test::differingPixels(mFirst, changed, 2), 20u) << what << " changed nothing";
        EXPECT_EQ(
            test::differingPixels(freshFrame(freshScene ? *freshScene : mScene, fresh), changed, 1),
            0u)
            << what;
        EXPECT_EQ(internals(*mRenderer).strategy()->report().bundlesRecorded, mRecorded) << what;
        EXPECT_TRUE(test::vulkanContext()->checkNoErrors(what).ok());
    }

    scene::SceneData mScene;
    std::shared_ptr<Environment> mEnvironment;
    RendererOptions mOptions;
    std::unique_ptr<Renderer> mRenderer;
    image::ImageRgba8 mFirst;
    std::uint64_t mRecorded = 0;
};

TEST_P(BundleLightingTest, ExposureAndToneMapping) {
    RendererOptions changed = mOptions;
    changed.toneMapping.exposure = 2.5f;
    changed.toneMapping.toneMapping = ToneMapping::AcesHill;
    ASSERT_TRUE(mRenderer->setToneMapping(changed.toneMapping).ok());
    expectSameAsFresh(changed, "exposure and tone mapping");
}

TEST_P(BundleLightingTest, EnvironmentIntensityAndRotation) {
    RendererOptions changed = mOptions;
    changed.lighting.environmentIntensity = 0.4f;
    changed.lighting.environmentRotationRadians = 2.0f;
    mRenderer->setLighting(changed.lighting);
    expectSameAsFresh(changed, "environment intensity and rotation");
}

TEST_P(BundleLightingTest, PunctualLightParameters) {
    scene::SceneData brighter = litScene();
    brighter.lights[0].intensity = 30.0f;
    brighter.lights[0].color = {0.2f, 1.0f, 0.4f};
    ASSERT_TRUE(mRenderer->updateLight(0, brighter.lights[0], brighter.lightInstances[0]).ok());
    expectSameAsFresh(mOptions, "light colour and intensity", &brighter);
    EXPECT_FALSE(mRenderer->updateLight(5, brighter.lights[0], brighter.lightInstances[0]).ok());
}

TEST_P(BundleLightingTest, MaterialFactors) {
    scene::SceneData edited = litScene();
    edited.materials[0].roughnessFactor = 0.9f;
    edited.materials[0].metallicFactor = 0.2f;
    edited.materials[1].emissiveFactor = {0.3f, 0.0f, 0.0f};
    ASSERT_TRUE(mRenderer->updateMaterial(scene::MaterialId{0u}, edited.materials[0]).ok());
    ASSERT_TRUE(mRenderer->updateMaterial(scene::MaterialId{1u}, edited.materials[1]).ok());
    expectSameAsFresh(mOptions, "material factors", &edited);
}

// A new environment is computed into the same textures: the frame bind group, and so the
// bundle, stays valid.
TEST_P(BundleLightingTest, LoadingANewEnvironmentDoesNotReRecord) {
    const image::HdrImage warm = image::makeUniformEnvironment(1.5f, 0.8f, 0.3f, 64);
    ASSERT_TRUE(mRenderer->loadEnvironment(warm).ok());
    RendererOptions fresh = mOptions;
    fresh.environment = ownEnvironment(warm);
    expectSameAsFresh(fresh, "a new environment");
}

// Another environment, already built (encore batch keeps one per file): a prepared strategy
// keeps the one it was prepared with (its bind group binds it) until the next prepare(), which
// draws what a renderer created with the new one draws; and back again.
TEST_P(BundleLightingTest, SettingAnotherEnvironmentTakesEffectAtTheNextPrepare) {
    const std::shared_ptr<Environment> warm =
        ownEnvironment(image::makeUniformEnvironment(1.5f, 0.8f, 0.3f, 64));
    mRenderer->setEnvironment(warm);
    EXPECT_EQ(test::differingPixels(mFirst, frame(*mRenderer), 0), 0u) << "before prepare()";
    ASSERT_TRUE(mRenderer->prepare(mScene, GetParam()).ok());
    const image::ImageRgba8 changed = frame(*mRenderer);
    EXPECT_GT(test::differingPixels(mFirst, changed, 2), 20u) << "the environment did not change";
    RendererOptions fresh = mOptions;
    fresh.environment = warm;
    EXPECT_EQ(test::differingPixels(freshFrame(mScene, fresh), changed, 1), 0u);

    mRenderer->setEnvironment(mEnvironment);
    ASSERT_TRUE(mRenderer->prepare(mScene, GetParam()).ok());
    EXPECT_EQ(test::differingPixels(mFirst, frame(*mRenderer), 0), 0u);
    EXPECT_TRUE(test::vulkanContext()->checkNoErrors("switching environments").ok());
}

INSTANTIATE_TEST_SUITE_P(BundleStrategies,
                         BundleLightingTest,
                         ::testing::Values(StrategyKind::Bundles, StrategyKind::GpuCullingBundles),
                         [](const auto& info) { return test::strategyTestName(info.param); });

}  // namespace
}  // namespace encore::render
