// Beyond the device's limits: images larger than maxTextureDimension2D are downscaled with a
// warning, buffers beyond maxBufferSize or maxStorageBufferBindingSize fail with an error naming
// the limit and the numbers, and out-of-memory errors become error values. None of them may
// raise a WebGPU validation error.
//
// Dawn raises requested limits below WebGPU's defaults to the defaults, so the tests tighten
// Encore's own limits with ContextOptions::limitOverrides (see gpu/DeviceLimits.h); the texture
// test also runs against the device's real maxTextureDimension2D.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "GltfBuilder.h"
#include "GpuTestSupport.h"
#include "RenderTestSupport.h"
#include "TestPaths.h"
#include "core/Log.h"
#include "encore/render/Renderer.h"
#include "gpu/OutOfMemoryScope.h"
#include "gpu/Readback.h"
#include "render/BindingLimits.h"
#include "render/MaterialResources.h"
#include "render/SceneLimits.h"
#include "render/animation/GpuAnimation.h"
#include "scene/SceneGenerator.h"

namespace encore::render {
namespace {

constexpr std::uint32_t kSize = 64;
constexpr std::uint32_t kTextureLimit = 256;
constexpr std::uint64_t kStorageLimit = 64 * 1024;
constexpr std::uint64_t kBufferLimit = 128 * 1024;

// Collects warnings while alive; other messages go to the previous sink.
class WarningCapture {
  public:
    WarningCapture() {
        mPrevious = setLogSink([this](LogLevel level, std::string_view message) {
            if (level == LogLevel::Warning) {
                warnings.emplace_back(message);
            } else if (mPrevious) {
                mPrevious(level, message);
            }
        });
    }
    ~WarningCapture() { setLogSink(mPrevious); }
    std::vector<std::string> warnings;

  private:
    LogSink mPrevious;
};

// One context with small limits and one renderer on it for the whole suite (building the
// environment maps is what costs).
class DeviceLimitsTest : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        gpu::ContextOptions options;
        options.limitOverrides = {kTextureLimit, kBufferLimit, kStorageLimit};
        auto context = gpu::Context::create(options);
        if (!context) {
            return;
        }
        sContext = std::make_unique<gpu::Context>(std::move(*context));
        RendererOptions rendererOptions = test::pixelTestOptions(kSize, kSize);
        rendererOptions.environment = nullptr;  // The shared one lives on another device.
        rendererOptions.environmentOptions = test::testEnvironmentOptions();
        auto renderer = Renderer::create(*sContext, rendererOptions);
        if (renderer) {
            sRenderer = std::make_unique<Renderer>(std::move(*renderer));
        }
    }
    static void TearDownTestSuite() {
        sRenderer.reset();
        sContext.reset();
    }
    void SetUp() override {
        ASSERT_NE(sContext, nullptr) << "no context with limit overrides";
        ASSERT_EQ(sContext->adapterDescription().backend, wgpu::BackendType::Vulkan);
        ASSERT_NE(sRenderer, nullptr);
    }
    void TearDown() override {
        EXPECT_TRUE(sContext->checkNoErrors("the test").ok()) << "a WebGPU error was raised";
    }

    static std::unique_ptr<gpu::Context> sContext;
    static std::unique_ptr<Renderer> sRenderer;
};
std::unique_ptr<gpu::Context> DeviceLimitsTest::sContext;
std::unique_ptr<Renderer> DeviceLimitsTest::sRenderer;

Result<scene::SceneData> generatedScene(std::uint32_t objects) {
    scene::GeneratorOptions generator;
    generator.objectCount = objects;
    generator.meshCount = 3;
    generator.materialCount = 2;
    auto glb = scene::generateSceneGlb(generator);
    if (!glb) {
        return glb.error();
    }
    return scene::loadSceneFromMemory(*glb, {}, "generated.glb");
}

TEST_F(DeviceLimitsTest, TheContextReportsItsOverridesBelowWhatDawnGranted) {
    const gpu::DeviceLimits& limits = sContext->limits();
    EXPECT_EQ(limits.maxTextureDimension2D, kTextureLimit);
    EXPECT_EQ(limits.maxBufferSize, kBufferLimit);
    EXPECT_EQ(limits.maxStorageBufferBindingSize, kStorageLimit);
    // What Dawn itself granted: never below WebGPU's defaults (the reason for the overrides).
    wgpu::Limits granted{};
    sContext->device().GetLimits(&granted);
    EXPECT_GE(granted.maxTextureDimension2D, 8192u);
    EXPECT_GE(granted.maxStorageBufferBindingSize, 134217728u);
}

// A 600x300 texture, red on the left and blue on the right, on a quad: drawn from a 256x128
// texture, the halves stay where they were.
TEST_F(DeviceLimitsTest, ATextureBeyondTheLimitIsDownscaledAndStillDrawn) {
    const auto dir = test::makeTempDir("device-limits-texture");
    image::ImageRgba8 picture{600, 300, {}};
    for (std::uint32_t y = 0; y < picture.height; ++y) {
        for (std::uint32_t x = 0; x < picture.width; ++x) {
            const bool left = x < picture.width / 2;
            picture.pixels.insert(picture.pixels.end(), {std::uint8_t(left ? 255 : 0), 0,
                                                         std::uint8_t(left ? 0 : 255), 255});
        }
    }
    ASSERT_TRUE(image::writePng(dir / "wide.png", picture).ok());
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
    const auto texcoords = builder.addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const auto indices = builder.addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    const auto material = builder.addMaterial({.baseColorTexture = builder.addTexture("wide.png")});
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", positions}, {"TEXCOORD_0", texcoords}},
                         .indices = indices,
                         .material = material});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = scene::loadScene(builder.writeGltf(dir, "quad"));
    ASSERT_TRUE(scene.ok()) << scene.error().message;

    WarningCapture capture;
    ASSERT_TRUE(sRenderer->prepare(*scene, StrategyKind::Bundles).ok());
    ASSERT_EQ(capture.warnings.size(), 1u);
    const std::string& warning = capture.warnings.front();
    EXPECT_NE(warning.find("wide.png"), std::string::npos) << warning;
    EXPECT_NE(warning.find("600x300"), std::string::npos) << warning;
    EXPECT_NE(warning.find("256x128"), std::string::npos) << warning;
    EXPECT_NE(warning.find("maxTextureDimension2D (256)"), std::string::npos) << warning;

    const Camera camera = test::frontCamera();
    sRenderer->renderFrame(camera);
    auto frame = sRenderer->readImage();
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    const auto [leftX, leftY] = test::pixelOf(camera, {-0.6f, 0.0f, 0.0f}, kSize, kSize);
    const auto [rightX, rightY] = test::pixelOf(camera, {0.6f, 0.0f, 0.0f}, kSize, kSize);
    EXPECT_LE(test::channelDistance(test::pixelAt(*frame, leftX, leftY), {255, 0, 0, 255}), 2)
        << test::describe(test::pixelAt(*frame, leftX, leftY));
    EXPECT_LE(test::channelDistance(test::pixelAt(*frame, rightX, rightY), {0, 0, 255, 255}), 2)
        << test::describe(test::pixelAt(*frame, rightX, rightY));
}

// The device's own limit, without overrides: one texel row longer than the device allows.
TEST(DeviceTextureLimitTest, AnImageWiderThanTheDeviceAllowsIsDownscaledToItsLimit) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::uint32_t limit = context->limits().maxTextureDimension2D;
    scene::SceneData scene;
    scene::Image wide;
    wide.name = "wide.png";
    wide.width = limit + limit / 10;
    wide.height = 11;
    for (std::uint32_t i = 0; i < wide.width * wide.height; ++i) {
        wide.rgba8.insert(wide.rgba8.end(), {200, 100, 50, 255});
    }
    scene.images.push_back(std::move(wide));
    scene.samplers.emplace_back();
    scene.textures.push_back({scene::ImageId{0u}, scene::SamplerId{0u}});
    scene::Material material;
    material.baseColorTexture = scene::TextureRef{scene::TextureId{0u}};
    scene.materials.push_back(material);

    shaders::ShaderLibrary shaders(context->device());
    const BindGroupLayouts layouts = BindGroupLayouts::create(context->device());
    WarningCapture capture;
    auto resources = MaterialResources::create(context->device(), context->queue(), shaders,
                                               layouts, scene, SampledTextures::baseColorOnly());
    ASSERT_TRUE(resources.ok()) << resources.error().message;
    const wgpu::Texture* texture = resources->texture(scene::ImageId{0u}, ColorSpace::Srgb);
    ASSERT_NE(texture, nullptr);
    EXPECT_EQ(texture->GetWidth(), limit);
    EXPECT_EQ(texture->GetHeight(), 10u);  // 11 / 1.1.
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find(std::to_string(limit) + "x10"), std::string::npos)
        << capture.warnings[0];
    auto pixels = gpu::readTexture(*context, *texture);
    ASSERT_TRUE(pixels.ok()) << pixels.error().message;
    EXPECT_LE(test::channelDistance(test::pixelAt(*pixels, limit - 1, 9), {200, 100, 50, 255}), 1);
    EXPECT_TRUE(context->checkNoErrors("downscaling").ok());
}

// An environment panorama beyond the device's own limit is downscaled the same way.
TEST(DeviceTextureLimitTest, APanoramaWiderThanTheDeviceAllowsIsDownscaled) {
    ENCORE_REQUIRE_VULKAN(context);
    const std::uint32_t limit = context->limits().maxTextureDimension2D;
    image::HdrImage panorama;
    panorama.width = limit + limit / 10;
    panorama.height = 11;
    panorama.rgb.assign(std::size_t(panorama.width) * panorama.height * 3, 0.5f);
    shaders::ShaderLibrary shaders(context->device());
    WarningCapture capture;
    auto environment = Environment::create(context->device(), context->queue(), shaders, panorama,
                                           test::testEnvironmentOptions());
    ASSERT_TRUE(environment.ok()) << environment.error().message;
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("environment panorama is " + std::to_string(panorama.width) +
                                       "x11"),
              std::string::npos)
        << capture.warnings[0];
    EXPECT_NE(capture.warnings[0].find("downscaled to " + std::to_string(limit) + "x10"),
              std::string::npos)
        << capture.warnings[0];
    EXPECT_TRUE(context->checkNoErrors("the environment").ok());
}

// 600 instances need 76,800 bytes of instance transforms: too much for a 64 KiB storage
// binding. Strategies that bind them as storage refuse the scene by name; the node-by-node
// strategies, which do not, draw it.
TEST_F(DeviceLimitsTest, InstanceTransformsBeyondTheStorageLimitAreAClearError) {
    auto scene = generatedScene(600);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (StrategyKind kind :
         {StrategyKind::Instancing, StrategyKind::Bundles, StrategyKind::GpuCullingBundles}) {
        auto prepared = sRenderer->prepare(*scene, kind);
        ASSERT_FALSE(prepared.ok()) << strategyName(kind);
        EXPECT_EQ(prepared.error().code, ErrorCode::LimitExceeded);
        const std::string& message = prepared.error().message;
        EXPECT_NE(message.find("maxStorageBufferBindingSize (65536 bytes)"), std::string::npos)
            << message;
        EXPECT_NE(message.find("76800 bytes"), std::string::npos) << message;
        EXPECT_NE(message.find("600 instances"), std::string::npos) << message;
    }
    ASSERT_TRUE(sRenderer->prepare(*scene, StrategyKind::PipelineCache).ok());
    sRenderer->renderFrame(Camera::framing(scene->bounds, 1.0f));
    auto frame = sRenderer->readImage();
    ASSERT_TRUE(frame.ok()) << frame.error().message;
}

// 12,000 vertices: 144,000 bytes of positions, beyond a 128 KiB maxBufferSize, whichever way a
// strategy uploads them.
TEST_F(DeviceLimitsTest, VertexDataBeyondTheBufferLimitIsAClearError) {
    std::vector<glm::vec3> positions;
    for (int i = 0; i < 12000; ++i) {
        const float x = float(i % 3 == 1);
        const float y = float(i % 3 == 2);
        positions.push_back({x, y, -0.001f * float(i / 3)});
    }
    test::GltfBuilder builder;
    const auto mesh =
        builder.addMesh({.attributes = {{"POSITION", builder.addPositions(positions)}}});
    builder.addScene({builder.addNode({.mesh = mesh})});
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "large-mesh.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (StrategyKind kind : allStrategies()) {
        auto prepared = sRenderer->prepare(*scene, kind);
        ASSERT_FALSE(prepared.ok()) << strategyName(kind);
        EXPECT_EQ(prepared.error().code, ErrorCode::LimitExceeded);
        const std::string& message = prepared.error().message;
        EXPECT_NE(message.find("maxBufferSize (131072 bytes)"), std::string::npos) << message;
        EXPECT_NE(message.find("144000 bytes"), std::string::npos) << message;
        EXPECT_NE(message.find("mesh 0, primitive 0"), std::string::npos) << message;
    }
}

// GPU culling keeps two visible-instance lists per draw (one per occlusion-culling phase) and a
// visibility word per instance: one mesh of 40 primitives with 500 instances fits the 64 KiB
// storage limit as instance transforms (64,000 bytes) but not as 80 lists of 512 entries, which
// pass even the 128 KiB buffer limit; the culling strategies say so, the others draw.
TEST_F(DeviceLimitsTest, CullingListsBeyondTheStorageLimitAreAClearError) {
    test::GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}});
    std::vector<test::GltfBuilder::PrimitiveDesc> primitives(40);
    for (auto& primitive : primitives) {
        primitive.attributes = {{"POSITION", positions}};
    }
    const auto mesh = builder.addMesh(primitives, "forty primitives");
    std::vector<std::uint32_t> nodes;
    for (int i = 0; i < 500; ++i) {
        nodes.push_back(
            builder.addNode({.mesh = mesh, .translation = glm::vec3(i % 25, i / 25, 0)}));
    }
    builder.addScene(nodes);
    auto scene = scene::loadSceneFromMemory(builder.toGlb(), {}, "many-primitives.glb");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    for (StrategyKind kind : {StrategyKind::GpuCulling, StrategyKind::GpuCullingBundles}) {
        auto prepared = sRenderer->prepare(*scene, kind);
        ASSERT_FALSE(prepared.ok()) << strategyName(kind);
        EXPECT_EQ(prepared.error().code, ErrorCode::LimitExceeded);
        const std::string& message = prepared.error().message;
        EXPECT_NE(message.find("visible-instance lists of 40 culled draws over 500 instances"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find("a buffer of 165840 bytes, larger than the device's maxBufferSize "
                               "(131072 bytes)"),
                  std::string::npos)
            << message;
    }
    ASSERT_TRUE(sRenderer->prepare(*scene, StrategyKind::Bundles).ok());
    sRenderer->renderFrame(Camera::framing(scene->bounds, 1.0f));
    ASSERT_TRUE(sRenderer->readImage().ok());
}

// Dawn reports a failed allocation as an out-of-memory error, through error scopes or the
// uncaptured-error callback; Device::InjectError produces one the same way.
TEST(OutOfMemoryTest, OutOfMemoryErrorsBecomeErrorValuesNamingTheWork) {
    ENCORE_REQUIRE_VULKAN(context);
    {
        gpu::OutOfMemoryScope scope(*context);
        context->device().InjectError(wgpu::ErrorType::OutOfMemory, "no room for 3 GiB");
        auto finished = scope.finish("Preparing 'big.glb' for strategy bundles");
        ASSERT_FALSE(finished.ok());
        EXPECT_EQ(finished.error().code, ErrorCode::OutOfMemory);
        EXPECT_EQ(finished.error().message,
                  "Preparing 'big.glb' for strategy bundles: the GPU ran out of memory (no room "
                  "for 3 GiB).");
    }
    {
        gpu::OutOfMemoryScope scope(*context);
        EXPECT_TRUE(scope.finish("nothing").ok());
    }
    // Outside any scope: the context's error log classifies it.
    context->device().InjectError(wgpu::ErrorType::OutOfMemory, "no room at all");
    auto checked = context->checkNoErrors("Rendering");
    ASSERT_FALSE(checked.ok());
    EXPECT_EQ(checked.error().code, ErrorCode::OutOfMemory);
    EXPECT_NE(checked.error().message.find("Rendering: the GPU ran out of memory (no room at all)"),
              std::string::npos)
        << checked.error().message;
    EXPECT_TRUE(context->checkNoErrors("after").ok());
}

// The animation storage buffers are checked before anything is created: morph deltas
// (3 x 16 bytes per target vertex) and joint matrices (128 bytes per joint). No device needed.
TEST(AnimationLimitsTest, MorphDeltasAndJointsBeyondAStorageBindingAreRefused) {
    gpu::DeviceLimits limits;
    limits.maxStorageBufferBindingSize = 64 * 1024;
    scene::SceneData morphed;
    scene::Primitive primitive;
    primitive.vertexCount = 2000;  // 96,000 bytes of deltas for one target.
    primitive.targets.resize(1);
    morphed.meshes.push_back({});
    morphed.meshes[0].primitives.push_back(primitive);
    auto refused = checkSceneWithinLimits(limits, morphed, StrategyKind::Bundles);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(refused.error().message.find("morph target deltas"), std::string::npos)
        << refused.error().message;
    morphed.meshes[0].primitives[0].vertexCount = 1000;  // 48,000 bytes fit.
    EXPECT_TRUE(checkSceneWithinLimits(limits, morphed, StrategyKind::Bundles).ok());

    scene::SceneData skinned;
    skinned.skins.push_back({});
    skinned.skins[0].joints.resize(600);  // 76,800 bytes of joint matrices.
    refused = checkSceneWithinLimits(limits, skinned, StrategyKind::Naive);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("joint matrices"), std::string::npos)
        << refused.error().message;
}

// GPU-evaluated animation checks its keyframes and records before creating anything.
TEST(AnimationLimitsTest, GpuAnimationBeyondAStorageBindingIsRefused) {
    gpu::DeviceLimits limits;
    limits.maxStorageBufferBindingSize = 64 * 1024;
    scene::SceneData animated;
    animated.animations.push_back({});
    animated.animations[0].samplers.push_back({});
    auto& sampler = animated.animations[0].samplers[0];
    for (int k = 0; k < 10000; ++k) {
        sampler.times.push_back(float(k));           // 40,000 bytes:
        sampler.values.push_back(-1.0f - float(k));  // 80,000 with the values.
    }
    auto refused = GpuAnimation::checkLimits(limits, animated);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(refused.error().message.find("animation keyframes"), std::string::npos)
        << refused.error().message;
    animated.animations[0].samplers[0].values.resize(5000);  // 60,000 bytes fit.
    EXPECT_TRUE(GpuAnimation::checkLimits(limits, animated).ok());
    // Keyframes equal to stored ones are shared, not stored again.
    animated.animations.push_back(animated.animations[0]);
    EXPECT_TRUE(GpuAnimation::checkLimits(limits, animated).ok());
    animated.animations.pop_back();

    animated.skins.push_back({});
    animated.skins[0].joints.resize(1000);  // 80,000 bytes of joint records.
    refused = GpuAnimation::checkLimits(limits, animated);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("1000 joints"), std::string::npos)
        << refused.error().message;
}

// The context asks for more sampled textures per shader stage than WebGPU's default 16 (the
// material texture slots), as many as the adapter offers up to 48, and the device grants them.
TEST(SampledTextureLimitTest, TheDeviceGrantsTheSampledTexturesItWasAskedFor) {
    ENCORE_REQUIRE_VULKAN(context);
    wgpu::Limits adapter{};
    ASSERT_EQ(context->adapter().GetLimits(&adapter), wgpu::Status::Success);
    wgpu::Limits granted{};
    ASSERT_EQ(context->device().GetLimits(&granted), wgpu::Status::Success);
    const std::uint32_t wanted = std::min(adapter.maxSampledTexturesPerShaderStage,
                                          gpu::kRequestedSampledTexturesPerShaderStage);
    EXPECT_GE(granted.maxSampledTexturesPerShaderStage, wanted);
    EXPECT_EQ(context->limits().maxSampledTexturesPerShaderStage,
              granted.maxSampledTexturesPerShaderStage);
    EXPECT_GE(context->limits().maxSampledTexturesPerShaderStage, kStageSampledTextures);
}

// A device with fewer sampled textures per stage than the material pipelines bind is refused
// when the renderer is made, with the numbers, rather than failing pipeline validation later.
TEST(SampledTextureLimitTest, AnAdapterWithTooFewSampledTexturesIsAClearError) {
    gpu::DeviceLimits limits;
    limits.maxSampledTexturesPerShaderStage = kStageSampledTextures - 1;
    auto refused = checkBindingLimits(limits, "tiny adapter");
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::LimitExceeded);
    EXPECT_EQ(refused.error().message,
              "The adapter 'tiny adapter' offers " + std::to_string(kStageSampledTextures - 1) +
                  " sampled textures per shader stage (maxSampledTexturesPerShaderStage), fewer "
                  "than the " +
                  std::to_string(kStageSampledTextures) + " Encore's materials bind (" +
                  std::to_string(kMaterialTextureSlotCount) +
                  " texture slots and 2 for the environment and the transmission background).");
    limits.maxSampledTexturesPerShaderStage = kStageSampledTextures;
    EXPECT_TRUE(checkBindingLimits(limits, "tiny adapter").ok());

    // Through the renderer: a context whose limit is overridden below the need.
    gpu::ContextOptions options;
    options.limitOverrides.maxSampledTexturesPerShaderStage = kStageSampledTextures - 1;
    auto context = gpu::Context::create(options);
    ASSERT_TRUE(context.ok()) << context.error().message;
    RendererOptions rendererOptions = test::pixelTestOptions(kSize, kSize);
    rendererOptions.environment = nullptr;  // The shared one lives on another device.
    rendererOptions.environmentOptions = test::testEnvironmentOptions();
    auto renderer = Renderer::create(*context, rendererOptions);
    ASSERT_FALSE(renderer.ok());
    EXPECT_EQ(renderer.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(renderer.error().message.find("maxSampledTexturesPerShaderStage"), std::string::npos)
        << renderer.error().message;
    EXPECT_TRUE(context->checkNoErrors("the refused renderer").ok());
}

}  // namespace
}  // namespace encore::render
