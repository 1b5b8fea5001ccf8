#include "render/renderer/RendererCore.h"

#include <chrono>

#include "core/Elapsed.h"
#include "encore/image/HdrImage.h"
#include "gpu/OutOfMemoryScope.h"
#include "render/BindingLimits.h"
#include "render/FramePasses.h"
#include "render/GpuScene.h"
#include "render/MipmapGenerator.h"
#include "render/PassTargets.h"
#include "render/PipelineCache.h"
#include "render/SampleIdPass.h"
#include "render/SceneLimits.h"
#include "render/TransmissionPass.h"
#include "render/TriangleHistory.h"
#include "render/renderer/CreateStrategy.h"
#include "render/visibility/KeptStrategyObjects.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::render {

namespace {

// Only the mesh shader that draws glTF materials writes the pass targets.
Result<void> checkPassTargetStrategy(bool passTargets, StrategyKind kind) {
    const bool meshMaterials = kind == StrategyKind::Materials || kind == StrategyKind::Bundles ||
                               kind == StrategyKind::GpuCulling ||
                               kind == StrategyKind::GpuCullingBundles;
    if (!passTargets || meshMaterials) {
        return {};
    }
    return makeError(ErrorCode::InvalidArgument,
                     "Pass targets need a strategy that draws glTF materials in its mesh shader "
                     "(materials, bundles, gpu-culling, gpu-culling-bundles), not " +
                         std::string(strategyName(kind)) + ".");
}

// Only strategies whose passes grow with the target can outgrow it (FramePasses::checkTarget).
Result<void> checkTarget(const Strategy& strategy, std::uint32_t width, std::uint32_t height) {
    const FramePasses* passes = strategy.framePasses();
    return passes ? passes->checkTarget(width, height) : Result<void>{};
}

}  // namespace

RendererCore::RendererCore(RendererCore&&) noexcept = default;
RendererCore& RendererCore::operator=(RendererCore&&) noexcept = default;
RendererCore::~RendererCore() = default;

Result<RendererCore> RendererCore::create(gpu::Context& context, const RendererOptions& options) {
    RendererCore renderer;
    renderer.mContext = &context;
    ENCORE_TRY(renderer.build(options));
    return renderer;
}

Result<void> RendererCore::build(const RendererOptions& options) {
    gpu::Context& context = *mContext;
    RendererCore& renderer = *this;
    renderer.mOptions = options;
    ENCORE_TRY(checkBindingLimits(context.limits(), context.adapterDescription().name));
    // Straight alpha needs the coverage that only the HDR target keeps.
    renderer.mOptions.target.hdr =
        options.target.hdr || options.toneMapping.background == BackgroundKind::Transparent;
    ENCORE_TRY_ASSIGN(renderer.mTarget,
                      RenderTarget::create(context.device(), renderer.mOptions.target));
    renderer.mShaders = std::make_unique<shaders::ShaderLibrary>(context.device());
    renderer.mLayouts =
        std::make_unique<BindGroupLayouts>(BindGroupLayouts::create(context.device()));
    std::shared_ptr<Environment> environment = options.environment;
    if (!environment) {
        const image::HdrImage panorama =
            options.environmentImage ? *options.environmentImage : image::makeStudioEnvironment();
        auto created = Environment::create(context.device(), context.queue(), *renderer.mShaders,
                                           panorama, options.environmentOptions);
        if (!created) {
            return created.error().withContext("Creating the environment");
        }
        environment = std::make_shared<Environment>(std::move(*created));
    }
    ENCORE_TRY_ASSIGN(auto lighting,
                      SceneLighting::create(context.device(), context.queue(), environment));
    renderer.mLighting = std::make_unique<SceneLighting>(std::move(lighting));
    renderer.mLighting->setParameters(options.lighting);
    renderer.mLighting->setDisplayMapping(options.toneMapping, !renderer.mTarget.hdr());
    renderer.mFrame =
        std::make_unique<FrameUniforms>(context.device(), *renderer.mLayouts, *renderer.mLighting);
    if (renderer.mTarget.hdr()) {
        ENCORE_TRY_ASSIGN(auto toneMapper,
                          ToneMapper::create(context.device(), context.queue(), *renderer.mShaders,
                                             renderer.mTarget, options.toneMapping));
        renderer.mToneMapper = std::make_unique<ToneMapper>(std::move(toneMapper));
    }
    if (renderer.mTarget.options().exactIds && renderer.mTarget.hdr() &&
        renderer.mTarget.sampleCount() > 1) {
        ENCORE_TRY_ASSIGN(auto ids, SampleIdPass::create(context.device(), *renderer.mShaders,
                                                         IdChannels::RedGreen));
        ids.bindSource(context.device(), renderer.mTarget.multisampledSceneView());
        renderer.mSceneIds = std::make_unique<SampleIdPass>(std::move(ids));
    }
    if (options.passTargets != PassTargets::None) {
        if (context.limits().maxColorAttachmentBytesPerSample < kPassTargetBytesPerSample) {
            return makeError(ErrorCode::LimitExceeded,
                             "Pass targets need " + std::to_string(kPassTargetBytesPerSample) +
                                 " colour attachment bytes per sample; the device has " +
                                 std::to_string(context.limits().maxColorAttachmentBytesPerSample) +
                                 ".");
        }
        ENCORE_TRY_ASSIGN(auto passTargets,
                          PassTargetTextures::create(context.device(), context.queue(),
                                                     *renderer.mShaders, renderer.mTarget));
        renderer.mPassTargets = std::make_unique<PassTargetTextures>(std::move(passTargets));
    }
    ENCORE_TRY_ASSIGN(auto background, EnvironmentBackground::create(
                                           context.device(), *renderer.mShaders,
                                           renderer.mLayouts->frame, renderer.mTarget.sceneFormat(),
                                           RenderTarget::kDepthFormat, options.target.sampleCount,
                                           renderer.mPassTargets ? kPassTargetCount : 0));
    renderer.mBackground = std::make_unique<EnvironmentBackground>(std::move(background));

    renderer.mSetup = std::make_unique<RenderSetup>();
    RenderSetup& setup = *renderer.mSetup;
    setup.device = context.device();
    setup.queue = context.queue();
    setup.context = &context;
    setup.shaders = renderer.mShaders.get();
    setup.layouts = renderer.mLayouts.get();
    setup.frame = renderer.mFrame.get();
    setup.colorFormat = renderer.mTarget.sceneFormat();
    setup.depthFormat = RenderTarget::kDepthFormat;
    setup.sampleCount = options.target.sampleCount;
    setup.passTargets = passTargetsVariant(options.passTargets);
    setup.mappingBudget = context.mappingBudget();
    setup.limits = context.limits();
    if (options.keepPipelines) {
        renderer.mKeptPipelines = std::make_unique<PipelineCache>(setup);
        setup.keptPipelines = renderer.mKeptPipelines.get();
        renderer.mKeptObjects = std::make_unique<KeptStrategyObjects>();
        setup.keptObjects = renderer.mKeptObjects.get();
    }
    ENCORE_TRY_ASSIGN(auto mipmaps, MipmapGenerator::create(context.device(), *renderer.mShaders));
    renderer.mMipmaps = std::make_unique<MipmapGenerator>(std::move(mipmaps));
    setup.mipmaps = renderer.mMipmaps.get();
    renderer.mMipmaps->setTimestamps(mStageTimestamps, gpuStageIndex(GpuStage::Mipmaps));
    return context.checkNoErrors("Creating the renderer");
}

void RendererCore::setStageTimestamps(gpu::StageTimestamps* timestamps) {
    mStageTimestamps = timestamps;
    if (mMipmaps) {
        mMipmaps->setTimestamps(timestamps, gpuStageIndex(GpuStage::Mipmaps));
    }
}

void RendererCore::setResourcePool(gpu::ResourcePool* pool) {
    mSetup->resources = pool;
}

Result<void> RendererCore::recoverFromDeviceLoss() {
    // Everything is rebuilt from what the CPU holds: the options as they are now, the
    // environment's panorama, the scene data and the strategy kind.
    RendererOptions options = mOptions;
    options.lighting = mLighting->parameters();
    const Environment& environment = mLighting->environment();
    options.environment = nullptr;
    options.environmentImage = std::make_shared<image::HdrImage>(environment.panorama());
    options.environmentOptions = environment.options();
    mPendingEnvironment.reset();  // Built on the lost device.
    // The animation as it played: a rebuilt player would start at rest with every animation.
    const Playback playing = playback();
    const std::optional<scene::VariantId> selectedVariant = variant();
    const std::optional<double> animationTime = mAnimationTime;
    mGpuAnimation.reset();
    mStrategy.reset();
    mTransmission.reset();
    mSetup->resources = nullptr;  // Its pool holds the lost device's objects: keep none.
    mGpuScene.reset();
    mPlayer.reset();
    mBackground.reset();
    mResolvedBackground.reset();
    mToneMapper.reset();
    mSceneIds.reset();
    mPassTargets.reset();
    mFrame.reset();
    mLighting.reset();
    mKeptPipelines.reset();
    mKeptObjects.reset();
    mMipmaps.reset();
    mSetup.reset();
    mLayouts.reset();
    mShaders.reset();
    mTarget = RenderTarget();
    ENCORE_TRY(mContext->recreateDevice());
    if (auto built = build(options); !built) {
        return built.error().withContext("Rebuilding the renderer after a device loss");
    }
    if (!mScene) {
        return {};
    }
    ENCORE_TRY(prepare(*mScene, mKind, mBundle));
    if (selectedVariant) {
        ENCORE_TRY(selectVariant(selectedVariant));
    }
    ENCORE_TRY(restorePlayback(playing));
    if (animationTime) {
        ENCORE_TRY(setAnimationTime(*animationTime));
    }
    return {};
}

Result<void> RendererCore::prepare(const scene::SceneData& scene,
                                   StrategyKind kind,
                                   bool bundle,
                                   const StagedUploads& staged) {
    const std::string what = "Preparing '" + scene.sourcePath.string() + "' for strategy " +
                             std::string(strategyName(kind)) + (bundle ? " (bundled)" : "");
    if (auto fits = checkSceneWithinLimits(mSetup->limits, scene, kind); !fits) {
        return fits.error().withContext(what);
    }
    mGpuAnimation.reset();
    if (mOptions.animation == AnimationEvaluation::Gpu) {
        if (auto fits = GpuAnimation::checkLimits(mSetup->limits, scene); !fits) {
            return fits.error().withContext("Preparing '" + scene.sourcePath.string() +
                                            "' for GPU animation");
        }
    }
    if (auto drawn = checkPassTargetStrategy(mPassTargets != nullptr, kind); !drawn) {
        return drawn.error().withContext(what);
    }
    PrepareTimes& times = mSetup->prepareTimes;
    times = {};
    auto start = std::chrono::steady_clock::now();
    if (mStrategy || mGpuScene) {
        mStrategy.reset();
        retireGpuScene();
        freeReleasedObjects();
    }
    times.release = millisecondsSince(start);
    start = std::chrono::steady_clock::now();
    applyPendingEnvironment();  // The strategy about to be prepared binds it.
    if (mLighting->setSceneLights(scene)) {
        mFrame->bindLighting(mContext->device(), *mLayouts, *mLighting);
    }
    mScene = &scene;
    if (mTriangleHistory) {
        setTriangleCounting(true);  // Counts of the previous strategy are not this one's.
    }
    mPlayer = std::make_unique<scene::AnimationPlayer>(scene);
    mPlayer->setMode(mPlaybackMode);
    mAnimationStats = {};
    mAnimationTime.reset();
    times.animation = millisecondsSince(start);
    start = std::chrono::steady_clock::now();
    // One scope for the scene and the strategy: each pop waits on the device.
    gpu::OutOfMemoryScope outOfMemory(*mContext);
    auto created = GpuScene::create(*mSetup, scene, mPlayer.get(), staged);
    times.scene = millisecondsSince(start);
    if (!created) {
        ENCORE_TRY(outOfMemory.finish(what));
        return created.error().withContext(what);
    }
    mGpuScene = std::move(*created);
    ++mSceneUploads;
    if (auto transmission = prepareTransmission(); !transmission) {
        ENCORE_TRY(outOfMemory.finish(what));
        return transmission.error().withContext(what);
    }
    return prepareStrategy(kind, bundle, what, outOfMemory);
}

Result<void> RendererCore::prepareTransmission() {
    const wgpu::Texture& background = mGpuScene->transmissionBackground();
    // Before the strategy records: the frame bind group it sets binds the background.
    mFrame->bindTransmission(mContext->device(), *mLayouts, *mLighting,
                             background ? background.CreateView() : wgpu::TextureView());
    mTransmission.reset();
    if (background) {
        ENCORE_TRY_ASSIGN(auto pass,
                          TransmissionPass::create(mContext->device(), *mShaders, background));
        mTransmission = std::make_unique<TransmissionPass>(std::move(pass));
    }
    return {};
}

Result<void> RendererCore::setStrategy(StrategyKind kind, bool bundle) {
    if (!mGpuScene) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    const std::string what = "Switching '" + mScene->sourcePath.string() + "' to strategy " +
                             std::string(strategyName(kind)) + (bundle ? " (bundled)" : "");
    if (auto fits = checkSceneWithinLimits(mSetup->limits, *mScene, kind); !fits) {
        return fits.error().withContext(what);
    }
    if (auto drawn = checkPassTargetStrategy(mPassTargets != nullptr, kind); !drawn) {
        return drawn.error().withContext(what);
    }
    mSetup->prepareTimes = {};
    const auto start = std::chrono::steady_clock::now();
    if (mGpuAnimation) {
        mGpuAnimation->copyInstancesTo({});  // Into the old strategy's buffers no more.
    }
    mStrategy.reset();
    freeReleasedObjects();
    mSetup->prepareTimes.release = millisecondsSince(start);
    applyPendingEnvironment();
    if (mTriangleHistory) {
        setTriangleCounting(true);
    }
    gpu::OutOfMemoryScope outOfMemory(*mContext);
    return prepareStrategy(kind, bundle, what, outOfMemory);
}

Result<void> RendererCore::createKeptObjects(StrategyKind kind) {
    if (!mKeptObjects || kind != StrategyKind::Visibility ||
        !mContext->device().HasFeature(kVisibilityFeature) || mKeptObjects->visibilityPipelines) {
        return {};
    }
    ENCORE_TRY_ASSIGN(mKeptObjects->visibilityPipelines, VisibilityPipelines::create(*mSetup));
    return mContext->checkNoErrors("Creating the visibility strategy's pipelines");
}

Result<void> RendererCore::prepareStrategy(StrategyKind kind,
                                           bool bundle,
                                           const std::string& what,
                                           gpu::OutOfMemoryScope& outOfMemory) {
    PrepareTimes& times = mSetup->prepareTimes;
    mKind = kind;
    mBundle = bundle;
    mSetup->pipelinesCreated = 0;
    mSetup->mappingBudget = mContext->mappingBudget();  // What the scenes left in use.
    auto start = std::chrono::steady_clock::now();
    auto strategy = createStrategy(kind, bundle);
    auto prepared = strategy->prepare(*mSetup, *mGpuScene);
    times.strategy = millisecondsSince(start);
    start = std::chrono::steady_clock::now();
    ENCORE_TRY(outOfMemory.finish(what));
    if (prepared) {
        prepared = checkTarget(*strategy, mTarget.width(), mTarget.height());
    }
    if (!prepared) {
        return prepared.error().withContext(what);
    }
    ENCORE_TRY(mContext->checkNoErrors(what));
    times.checks = millisecondsSince(start);
    mStrategy = std::move(strategy);
    const FramePasses* passes = mStrategy->framePasses();
    if (mTarget.sampleCount() > 1 && !mResolvedBackground && passes && passes->composesResolved()) {
        // Made by the first strategy that draws resolved passes (RendererFrame.cpp), not by
        // every multisampled renderer.
        ENCORE_TRY_ASSIGN(auto resolved,
                          EnvironmentBackground::create(mContext->device(), *mShaders,
                                                        mLayouts->frame, mTarget.sceneFormat(),
                                                        wgpu::TextureFormat::Undefined, 1));
        mResolvedBackground = std::make_unique<EnvironmentBackground>(std::move(resolved));
    }
    if (mOptions.animation == AnimationEvaluation::Gpu && !mGpuAnimation) {
        ENCORE_TRY(createGpuAnimation());  // Once per GPU scene.
    } else if (mGpuAnimation) {
        mGpuAnimation->copyInstancesTo(mStrategy->instanceTransformTargets().uniforms);
        if (mAnimationTime) {
            mGpuAnimationPending = true;  // The new strategy's node uniforms hold no pose yet.
        }
    }
    return {};
}

void RendererCore::freeReleasedObjects() {
    // Dawn frees objects once the GPU is done with them, on a later tick. Let that happen before
    // the next scene or strategy allocates: peak memory stays one scene's worth, and drivers that
    // map memory per object (lavapipe) stay below the kernel's limit.
    if (mOptions.prepareWaitsForIdle) {
        mContext->waitForIdle();
    }
    mContext->device().Tick();
}

void RendererCore::retireGpuScene() {
    if (mTransmission) {
        mTransmission.reset();
        mFrame->bindTransmission(mContext->device(), *mLayouts, *mLighting, {});
    }
    if (mGpuScene) {
        mRetiredUploadBytes += mGpuScene->uploadedBytes();
        mGpuScene.reset();
    }
}

std::uint64_t RendererCore::uploadedBytes() const {
    return mRetiredUploadBytes + (mGpuScene ? mGpuScene->uploadedBytes() : 0);
}

RendererStats RendererCore::stats() const {
    RendererStats stats;
    stats.strategy = mKind;
    stats.bundled = bundled();
    stats.pipelinesCreated = mSetup->pipelinesCreated;
    stats.bundlesRecorded = mStrategy ? mStrategy->report().bundlesRecorded : 0;
    stats.sceneUploads = mSceneUploads;
    stats.uploadedBytes = uploadedBytes();
    stats.prepare = mSetup->prepareTimes;
    stats.environmentBuildMilliseconds = mLighting->environment().lastBuildMilliseconds();
    return stats;
}

void RendererCore::releaseScene() {
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    mStrategy.reset();
    retireGpuScene();
    mPlayer.reset();
    mAnimationStats = {};
    mAnimationTime.reset();
    mScene = nullptr;
    applyPendingEnvironment();
    // As prepare() does before the next strategy: Dawn frees the objects on a later tick, so
    // let it happen now rather than hold the scene's memory until the next prepare.
    mContext->waitForIdle();
    mContext->device().Tick();
}

Result<void> RendererCore::resize(std::uint32_t width, std::uint32_t height) {
    if (mStrategy) {
        ENCORE_TRY(checkTarget(*mStrategy, width, height));
    }
    RenderTargetOptions options = mTarget.options();
    options.width = width;
    options.height = height;
    ENCORE_TRY_ASSIGN(mTarget, RenderTarget::create(mContext->device(), options));
    mOptions.target.width = width;
    mOptions.target.height = height;
    if (mToneMapper) {
        mToneMapper->bindTarget(mContext->device(), mTarget);
    }
    if (mSceneIds) {
        mSceneIds->bindSource(mContext->device(), mTarget.multisampledSceneView());
    }
    if (mPassTargets) {
        ENCORE_TRY_ASSIGN(
            auto passTargets,
            PassTargetTextures::create(mContext->device(), mContext->queue(), *mShaders, mTarget));
        *mPassTargets = std::move(passTargets);
    }
    return mContext->checkNoErrors("Resizing the render target to " + std::to_string(width) + "x" +
                                   std::to_string(height));
}

Result<void> RendererCore::updateInstance(std::size_t instance, const glm::mat4& world) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mGpuScene->updateInstance(instance, world));
    mStrategy->instanceMoved(instance, world);
    return {};
}

Result<void> RendererCore::updateMaterial(scene::MaterialId material,
                                          const scene::Material& value) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    return mGpuScene->updateMaterial(material, value);
}

Result<void> RendererCore::replaceBaseColorImage(scene::MaterialId material,
                                                 const scene::Image& image) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mGpuScene->replaceBaseColorImage(material, image));
    ENCORE_TRY(mStrategy->refresh());
    return mContext->checkNoErrors("Replacing a base colour image");
}

Result<void> RendererCore::selectVariant(std::optional<scene::VariantId> variant) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mGpuScene->selectVariant(variant));
    // The draws regroup now (pipelines a variant needs are created here, not in a frame);
    // bundles record again on their next frame.
    ENCORE_TRY(mStrategy->refresh());
    return mContext->checkNoErrors("Selecting a material variant");
}

std::optional<scene::VariantId> RendererCore::variant() const {
    return mGpuScene ? mGpuScene->variant() : std::nullopt;
}

void RendererCore::setLighting(const LightingParameters& parameters) {
    mLighting->setParameters(parameters);
}

Result<void> RendererCore::setToneMapping(const ToneMappingOptions& options) {
    if (options.background == BackgroundKind::Transparent && !mTarget.hdr()) {
        return makeError(ErrorCode::InvalidArgument,
                         "A transparent background needs an HDR render target: create the "
                         "renderer with a transparent background or RenderTargetOptions::hdr.");
    }
    mOptions.toneMapping = options;
    if (mToneMapper) {
        mToneMapper->setOptions(options);
    }
    mLighting->setDisplayMapping(options, !mTarget.hdr());
    return {};
}

void RendererCore::setEnvironment(std::shared_ptr<Environment> environment) {
    if (!environment) {
        return;
    }
    mPendingEnvironment = std::move(environment);
    if (!mStrategy) {
        applyPendingEnvironment();  // Nothing holds the frame bind group yet.
    }
}

void RendererCore::applyPendingEnvironment() {
    if (mPendingEnvironment && mPendingEnvironment != mLighting->sharedEnvironment()) {
        mLighting->setEnvironment(std::move(mPendingEnvironment));
        mFrame->bindLighting(mContext->device(), *mLayouts, *mLighting);
    }
    mPendingEnvironment.reset();
}

Result<void> RendererCore::loadEnvironment(const image::HdrImage& panorama) {
    ENCORE_TRY(mLighting->loadEnvironment(panorama));
    return mContext->checkNoErrors("Loading an environment");
}

Result<void> RendererCore::updateLight(std::size_t lightInstance,
                                       const scene::Light& light,
                                       const scene::LightInstance& placed) {
    return mLighting->updateLight(lightInstance, light, placed);
}

}  // namespace encore::render
