#include "encore/render/Renderer.h"

#include <chrono>

#include "core/Elapsed.h"
#include "encore/image/HdrImage.h"
#include "gpu/OutOfMemoryScope.h"
#include "gpu/Readback.h"
#include "gpu/TimedSubmit.h"
#include "render/GpuCuller.h"
#include "render/GpuScene.h"
#include "render/MipmapGenerator.h"
#include "render/PipelineCache.h"
#include "render/SceneLimits.h"
#include "render/TriangleHistory.h"

namespace encore::render {

Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<Renderer> Renderer::create(gpu::Context& context, const RendererOptions& options) {
    Renderer renderer;
    renderer.mContext = &context;
    ENCORE_TRY(renderer.build(options));
    return renderer;
}

Result<void> Renderer::build(const RendererOptions& options) {
    gpu::Context& context = *mContext;
    Renderer& renderer = *this;
    renderer.mOptions = options;
    // Straight alpha needs the coverage that only the HDR target keeps.
    renderer.mOptions.target.hdr =
        options.target.hdr || options.toneMapping.background == BackgroundKind::Transparent;
    auto target = RenderTarget::create(context.device(), renderer.mOptions.target);
    if (!target) {
        return target.error();
    }
    renderer.mTarget = std::move(*target);
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
    auto lighting = SceneLighting::create(context.device(), context.queue(), environment);
    if (!lighting) {
        return lighting.error();
    }
    renderer.mLighting = std::make_unique<SceneLighting>(std::move(*lighting));
    renderer.mLighting->setParameters(options.lighting);
    renderer.mLighting->setDisplayMapping(options.toneMapping, !renderer.mTarget.hdr());
    renderer.mFrame =
        std::make_unique<FrameUniforms>(context.device(), *renderer.mLayouts, *renderer.mLighting);
    if (renderer.mTarget.hdr()) {
        auto toneMapper = ToneMapper::create(context.device(), context.queue(), *renderer.mShaders,
                                             renderer.mTarget, options.toneMapping);
        if (!toneMapper) {
            return toneMapper.error();
        }
        renderer.mToneMapper = std::make_unique<ToneMapper>(std::move(*toneMapper));
    }
    auto background = EnvironmentBackground::create(
        context.device(), *renderer.mShaders, renderer.mLayouts->frame,
        renderer.mTarget.sceneFormat(), RenderTarget::kDepthFormat, options.target.sampleCount);
    if (!background) {
        return background.error();
    }
    renderer.mBackground = std::make_unique<EnvironmentBackground>(std::move(*background));

    renderer.mSetup = std::make_unique<RenderSetup>();
    RenderSetup& setup = *renderer.mSetup;
    setup.device = context.device();
    setup.queue = context.queue();
    setup.shaders = renderer.mShaders.get();
    setup.layouts = renderer.mLayouts.get();
    setup.frame = renderer.mFrame.get();
    setup.colorFormat = renderer.mTarget.sceneFormat();
    setup.depthFormat = RenderTarget::kDepthFormat;
    setup.sampleCount = options.target.sampleCount;
    setup.mappingBudget = context.mappingBudget();
    setup.limits = context.limits();
    if (options.keepPipelines) {
        renderer.mKeptPipelines = std::make_unique<PipelineCache>(setup);
        setup.keptPipelines = renderer.mKeptPipelines.get();
    }
    auto mipmaps = MipmapGenerator::create(context.device(), *renderer.mShaders);
    if (!mipmaps) {
        return mipmaps.error();
    }
    renderer.mMipmaps = std::make_unique<MipmapGenerator>(std::move(*mipmaps));
    setup.mipmaps = renderer.mMipmaps.get();
    renderer.mMipmaps->setTimestamps(mStageTimestamps, gpuStageIndex(GpuStage::Mipmaps));
    return context.checkNoErrors("Creating the renderer");
}

void Renderer::setStageTimestamps(gpu::StageTimestamps* timestamps) {
    mStageTimestamps = timestamps;
    if (mMipmaps) {
        mMipmaps->setTimestamps(timestamps, gpuStageIndex(GpuStage::Mipmaps));
    }
}

Result<void> Renderer::recoverFromDeviceLoss() {
    // Everything is rebuilt from what the CPU holds: the options as they are now, the
    // environment's panorama, the scene data and the strategy kind.
    RendererOptions options = mOptions;
    options.lighting = mLighting->parameters();
    const Environment& environment = mLighting->environment();
    options.environment = nullptr;
    options.environmentImage = std::make_shared<image::HdrImage>(environment.panorama());
    options.environmentOptions = environment.options();
    // The animation as it played: a rebuilt player would start at rest with every animation.
    const Playback playing = playback();
    const std::optional<double> animationTime = mAnimationTime;
    mGpuAnimation.reset();
    mStrategy.reset();
    mGpuScene.reset();
    mPlayer.reset();
    mBackground.reset();
    mToneMapper.reset();
    mFrame.reset();
    mLighting.reset();
    mKeptPipelines.reset();
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
    ENCORE_TRY(restorePlayback(playing));
    if (animationTime) {
        ENCORE_TRY(setAnimationTime(*animationTime));
    }
    return {};
}

Result<void> Renderer::prepare(const scene::SceneData& scene,
                               StrategyKind kind,
                               bool bundle,
                               StagedImages* staged) {
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
    PrepareTimes& times = mSetup->prepareTimes;
    times = {};
    auto start = std::chrono::steady_clock::now();
    if (mStrategy || mGpuScene) {
        // Dawn frees objects once the GPU is done with them, on a later tick. Let that happen
        // before the next scene allocates: peak memory stays one scene's worth, and drivers
        // that map memory per object (lavapipe) stay below the kernel's limit.
        mGpuAnimation.reset();
        mStrategy.reset();
        retireGpuScene();
        if (mOptions.prepareWaitsForIdle) {
            mContext->waitForIdle();
        }
        mContext->device().Tick();
    }
    times.release = millisecondsSince(start);
    start = std::chrono::steady_clock::now();
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
    {
        gpu::OutOfMemoryScope outOfMemory(*mContext);
        auto created = GpuScene::create(*mSetup, scene, mPlayer.get(), staged);
        times.scene = millisecondsSince(start);
        ENCORE_TRY(outOfMemory.finish(what));
        if (!created) {
            return created.error().withContext(what);
        }
        mGpuScene = std::move(*created);
        ++mSceneUploads;
    }
    return prepareStrategy(kind, bundle, what);
}

Result<void> Renderer::setStrategy(StrategyKind kind, bool bundle) {
    if (!mGpuScene) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    const std::string what = "Switching '" + mScene->sourcePath.string() + "' to strategy " +
                             std::string(strategyName(kind)) + (bundle ? " (bundled)" : "");
    if (auto fits = checkSceneWithinLimits(mSetup->limits, *mScene, kind); !fits) {
        return fits.error().withContext(what);
    }
    mSetup->prepareTimes = {};
    const auto start = std::chrono::steady_clock::now();
    if (mGpuAnimation) {
        mGpuAnimation->copyInstancesTo({});  // Into the old strategy's buffers no more.
    }
    mStrategy.reset();
    if (mOptions.prepareWaitsForIdle) {
        mContext->waitForIdle();
    }
    mContext->device().Tick();
    mSetup->prepareTimes.release = millisecondsSince(start);
    if (mTriangleHistory) {
        setTriangleCounting(true);
    }
    return prepareStrategy(kind, bundle, what);
}

Result<void> Renderer::prepareStrategy(StrategyKind kind, bool bundle, const std::string& what) {
    PrepareTimes& times = mSetup->prepareTimes;
    mKind = kind;
    mBundle = bundle;
    mSetup->pipelinesCreated = 0;
    mSetup->mappingBudget = mContext->mappingBudget();  // What the scenes left in use.
    auto start = std::chrono::steady_clock::now();
    auto strategy = createStrategy(kind, bundle);
    gpu::OutOfMemoryScope outOfMemory(*mContext);
    auto prepared = strategy->prepare(*mSetup, *mGpuScene);
    times.strategy = millisecondsSince(start);
    start = std::chrono::steady_clock::now();
    ENCORE_TRY(outOfMemory.finish(what));
    if (!prepared) {
        return prepared.error().withContext(what);
    }
    ENCORE_TRY(mContext->checkNoErrors(what));
    times.checks = millisecondsSince(start);
    mStrategy = std::move(strategy);
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

const AnimationBuffers* Renderer::animationBuffers() const {
    return mGpuScene ? mGpuScene->animation() : nullptr;
}

void Renderer::retireGpuScene() {
    if (mGpuScene) {
        mRetiredUploadBytes += mGpuScene->uploadedBytes();
        mGpuScene.reset();
    }
}

std::uint64_t Renderer::uploadedBytes() const {
    return mRetiredUploadBytes + (mGpuScene ? mGpuScene->uploadedBytes() : 0);
}

void Renderer::releaseScene() {
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    mStrategy.reset();
    retireGpuScene();
    mPlayer.reset();
    mAnimationStats = {};
    mAnimationTime.reset();
    mScene = nullptr;
    // As prepare() does before the next strategy: Dawn frees the objects on a later tick, so
    // let it happen now rather than hold the scene's memory until the next prepare.
    mContext->waitForIdle();
    mContext->device().Tick();
}

Result<void> Renderer::createGpuAnimation() {
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    if (!mGpuScene || !mScene) {
        return {};
    }
    const std::string what = "Preparing GPU animation of '" + mScene->sourcePath.string() + "'";
    gpu::OutOfMemoryScope outOfMemory(*mContext);
    auto created = GpuAnimation::create(mContext->device(), mContext->queue(), *mShaders,
                                        mSetup->limits, *mScene, mGpuScene->animation(),
                                        mGpuScene->instances().transformTargets());
    ENCORE_TRY(outOfMemory.finish(what));
    if (!created) {
        return created.error().withContext(what);
    }
    ENCORE_TRY(mContext->checkNoErrors(what));
    mGpuAnimation = std::move(*created);
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
        if (mStrategy) {
            mGpuAnimation->copyInstancesTo(mStrategy->instanceTransformTargets().uniforms);
        }
    }
    return {};
}

Result<void> Renderer::setAnimationEvaluation(AnimationEvaluation evaluation) {
    if (evaluation == mOptions.animation) {
        return {};
    }
    mOptions.animation = evaluation;
    if (!mStrategy) {
        return {};
    }
    if (evaluation == AnimationEvaluation::Gpu) {
        if (auto fits = GpuAnimation::checkLimits(mSetup->limits, *mScene); !fits) {
            mOptions.animation = AnimationEvaluation::Cpu;
            return fits.error().withContext("Switching '" + mScene->sourcePath.string() +
                                            "' to GPU animation");
        }
        return createGpuAnimation();
    }
    // Back to the CPU: a fresh player reports every instance, joint and weight as changed at
    // its first evaluate(), so everything the GPU wrote is overwritten.
    mGpuAnimation.reset();
    mGpuAnimationPending = false;
    const Playback playing = playback();
    mPlayer = std::make_unique<scene::AnimationPlayer>(*mScene);
    return restorePlayback(playing);
}

void Renderer::setPlaybackMode(scene::PlaybackMode mode) {
    mPlaybackMode = mode;
    if (mPlayer) {
        mPlayer->setMode(mode);
    }
}

Renderer::Playback Renderer::playback() const {
    if (!mPlayer) {
        return {};
    }
    return {{mPlayer->selection().begin(), mPlayer->selection().end()}, mPlayer->mode()};
}

Result<void> Renderer::restorePlayback(const Playback& playback) {
    mPlayer->setMode(playback.mode);
    ENCORE_TRY(mPlayer->select(playback.selection));
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
    }
    return {};
}

FrameResult Renderer::renderFrame(const Camera& camera, float timeSeconds,
                                  std::vector<RecordedCall>* trace) {
    return renderPasses(std::span(&camera, 1), timeSeconds, trace);
}

FrameResult Renderer::renderViews(std::span<const Camera> cameras, float timeSeconds) {
    return renderPasses(cameras, timeSeconds, nullptr);
}

const wgpu::PassTimestampWrites* Renderer::timestampWrites(GpuStage stage,
                                                           std::string_view label) {
    if (mTimer) {
        return mTimer->nextPass(label);
    }
    return mStageTimestamps ? mStageTimestamps->pass(gpuStageIndex(stage)) : nullptr;
}

FrameResult Renderer::renderPasses(std::span<const Camera> cameras, float timeSeconds,
                                   std::vector<RecordedCall>* trace) {
    FrameResult result;
    if (cameras.empty()) {
        return result;
    }
    const bool multiView = cameras.size() > 1;
    if (multiView) {
        mFrame->writeViews(mContext->device(), mContext->queue(), cameras, timeSeconds);
    } else {
        mFrame->update(mContext->queue(), cameras[0], timeSeconds);
    }
    FrameState state{cameras[0], cameras, timeSeconds, mTimer, mCullingCamera};
    state.culling = mOptions.culling;
    state.targetWidth = mTarget.width();
    state.targetHeight = mTarget.height();
    const bool twoPhases = !multiView && mStrategy && mStrategy->drawsInTwoPhases(state);
    if (twoPhases) {
        state.phase = DrawPhase::First;
    }

    const GpuCuller* culler = mStrategy ? mStrategy->culler() : nullptr;
    auto encodeFrame = [&](const wgpu::CommandEncoder& commandEncoder) {
    if (mGpuAnimation && mGpuAnimationPending) {
        mGpuAnimation->encode(commandEncoder);  // Before anything that reads its results.
        mGpuAnimationPending = false;
    }
    if (mStrategy) {
        mStrategy->beforePass(commandEncoder, state);
    }
    const std::uint32_t viewWidth = mTarget.width() / std::uint32_t(cameras.size());
    // One pass per view, or the two passes of a two-phase frame: the first keeps its colour and
    // depth for the second (multisampled: unresolved), which loads them and finishes the view.
    auto encodePass = [&](std::size_t view, DrawPhase phase) {
        // HDR: alpha is coverage, 0 where nothing is drawn, for the tone mapper's background.
        // Otherwise the background colour itself (linear: the sRGB target encodes the clear).
        const glm::vec3& background = mOptions.toneMapping.backgroundColor;
        wgpu::RenderPassColorAttachment color = mTarget.colorAttachment(
            mTarget.hdr() ? wgpu::Color{0.0, 0.0, 0.0, 0.0}
                          : wgpu::Color{background.r, background.g, background.b, 1.0});
        wgpu::RenderPassDepthStencilAttachment depth = mTarget.depthAttachment();
        if (view > 0 || phase == DrawPhase::Second) {
            color.loadOp = wgpu::LoadOp::Load;  // Keep the views (or the phase) drawn before.
        }
        if (multiView) {
            color.storeOp = wgpu::StoreOp::Store;  // Multisampled contents survive the passes.
            if (view + 1 < cameras.size()) {
                // A resolve writes the whole target, whatever the viewport: resolve once, after
                // the last view, rather than the whole wide target once per view.
                color.resolveTarget = nullptr;
            }
            // Depth likewise: cleared once for the whole target and kept between the passes,
            // rather than cleared whole by each (each view tests only its own strip).
            if (view > 0) {
                depth.depthLoadOp = wgpu::LoadOp::Load;
            }
            if (view + 1 < cameras.size()) {
                depth.depthStoreOp = wgpu::StoreOp::Store;
            }
        }
        if (phase == DrawPhase::First) {
            color.storeOp = wgpu::StoreOp::Store;
            color.resolveTarget = nullptr;  // The second pass resolves.
            depth.depthStoreOp = wgpu::StoreOp::Store;
        } else if (phase == DrawPhase::Second) {
            depth.depthLoadOp = wgpu::LoadOp::Load;
        }
        wgpu::RenderPassDescriptor passDescriptor{};
        passDescriptor.label = phase == DrawPhase::First    ? "encore frame (first phase)"
                               : phase == DrawPhase::Second ? "encore frame (second phase)"
                                                            : "encore frame";
        passDescriptor.colorAttachmentCount = 1;
        passDescriptor.colorAttachments = &color;
        passDescriptor.depthStencilAttachment = &depth;
        passDescriptor.timestampWrites = timestampWrites(
            GpuStage::Scene, phase == DrawPhase::First    ? "scene (first phase)"
                             : phase == DrawPhase::Second ? "scene (second phase)"
                                                          : "scene");
        wgpu::RenderPassEncoder pass = commandEncoder.BeginRenderPass(&passDescriptor);
        if (multiView) {
            pass.SetViewport(float(view * viewWidth), 0.0f, float(viewWidth),
                             float(mTarget.height()), 0.0f, 1.0f);
            // Clipping keeps a view's fragments inside its viewport already; the scissor makes
            // sure no rounding reaches the neighbouring strips, whose colour and depth persist.
            pass.SetScissorRect(view * viewWidth, 0, viewWidth, mTarget.height());
        }
        if (mOptions.toneMapping.background == BackgroundKind::Environment &&
            phase != DrawPhase::Second) {
            mBackground->draw(pass, mFrame->bindGroup());
        }
        if (mStrategy) {
            RenderEncoder encoder(pass, result.counters);
            encoder.setTrace(trace);
            FrameState viewState = state;
            viewState.camera = cameras[view];
            viewState.phase = phase;
            mStrategy->encode(encoder, viewState);
        }
        pass.End();
    };
    if (twoPhases) {
        encodePass(0, DrawPhase::First);
        mStrategy->betweenPhases(commandEncoder, state, mTarget.depthTexture());
        encodePass(0, DrawPhase::Second);
    } else {
        for (std::size_t view = 0; view < cameras.size(); ++view) {
            if (multiView) {
                mFrame->selectView(commandEncoder, view);
            }
            encodePass(view, DrawPhase::Whole);
        }
    }
    // After the last pass: a two-phase frame counts in both culling passes.
    if (mTriangleHistory && culler && culler->indirectArguments()) {
        mTriangleHistory->record(commandEncoder, culler->indirectArguments(),
                                 culler->drawnTrianglesOffset());
    }
    if (mToneMapper) {
        // The GPU timer times the scene passes only, as benchmarks report them.
        mToneMapper->encode(commandEncoder, mTarget,
                            mTimer ? nullptr : timestampWrites(GpuStage::ToneMapping));
    }
    };
    const gpu::SubmitTiming timing = gpu::submitTimed(*mContext, mTimer, encodeFrame);
    result.encodeMilliseconds = timing.encodeMilliseconds;
    result.submitMilliseconds = timing.submitMilliseconds;
    result.gpuMilliseconds = timing.gpuMilliseconds;
    if (mStrategy) {
        result.bundleContents = mStrategy->bundleContents();
    }
    // Bundles and indirect draws replay per view; counters already sum the direct draws.
    result.trianglesSubmitted =
        result.counters.triangles +
        cameras.size() *
            (result.bundleContents.triangles + (culler ? submittedTriangles(culler->draws()) : 0));
    return result;
}

void Renderer::setTriangleCounting(bool on) {
    mTriangleHistory = on ? std::make_unique<TriangleHistory>(mContext->device()) : nullptr;
}

Result<std::vector<std::uint64_t>> Renderer::takeDrawnTriangles() {
    if (!mTriangleHistory) {
        return std::vector<std::uint64_t>{};
    }
    return mTriangleHistory->take(*mContext);
}

Result<void> Renderer::resize(std::uint32_t width, std::uint32_t height) {
    RenderTargetOptions options = mTarget.options();
    options.width = width;
    options.height = height;
    auto target = RenderTarget::create(mContext->device(), options);
    if (!target) {
        return target.error();
    }
    mTarget = std::move(*target);
    mOptions.target.width = width;
    mOptions.target.height = height;
    if (mToneMapper) {
        mToneMapper->bindTarget(mContext->device(), mTarget);
    }
    return mContext->checkNoErrors("Resizing the render target to " + std::to_string(width) +
                                   "x" + std::to_string(height));
}

Result<void> Renderer::updateInstance(std::size_t instance, const glm::mat4& world) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mGpuScene->updateInstance(instance, world));
    mStrategy->instanceMoved(instance, world);
    return {};
}

Result<void> Renderer::selectAnimation(std::string_view nameOrIndex) {
    if (!mPlayer) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    if (nameOrIndex.empty()) {
        mPlayer->selectAll();
    } else {
        ENCORE_TRY(mPlayer->select(nameOrIndex));
    }
    if (mGpuAnimation) {
        mGpuAnimation->select(mContext->queue(), mPlayer->selection());
    }
    return {};
}

Result<void> Renderer::setAnimationTime(double seconds) {
    if (!mStrategy || !mPlayer) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    mAnimationTime = seconds;
    if (mOptions.animation == AnimationEvaluation::Gpu) {
        AnimationFrameStats stats;
        stats.evaluation = AnimationEvaluation::Gpu;
        if (mGpuAnimation) {
            mGpuAnimation->setTime(mContext->queue(), seconds, mPlayer->mode());
            mGpuAnimationPending = true;
            stats.gpu = mGpuAnimation->stats();
            stats.bytesWritten = stats.gpu.bytesPerFrame;
        }
        mAnimationStats = stats;
        return {};
    }
    mPlayer->evaluate(seconds);
    AnimationFrameStats stats;
    stats.player = mPlayer->stats();
    const auto worlds = mPlayer->instanceWorlds();
    for (std::uint32_t instance : mPlayer->changedInstances()) {
        ENCORE_TRY(mGpuScene->updateInstance(instance, worlds[instance]));
        mStrategy->instanceMoved(instance, worlds[instance]);
        ++stats.instancesWritten;
    }
    stats.bytesWritten = std::uint64_t(stats.instancesWritten) * sizeof(TransformUniform);
    stats.upload = mGpuScene->writeAnimation(*mPlayer);
    stats.bytesWritten += stats.upload.bytesWritten;
    mAnimationStats = stats;
    return {};
}

Result<void> Renderer::updateMaterial(scene::MaterialId material, const scene::Material& value) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    return mGpuScene->updateMaterial(material, value);
}

Result<void> Renderer::replaceBaseColorImage(scene::MaterialId material,
                                             const scene::Image& image) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mGpuScene->replaceBaseColorImage(material, image));
    ENCORE_TRY(mStrategy->refresh());
    return mContext->checkNoErrors("Replacing a base colour image");
}

void Renderer::setLighting(const LightingParameters& parameters) {
    mLighting->setParameters(parameters);
}

Result<void> Renderer::setToneMapping(const ToneMappingOptions& options) {
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

Result<void> Renderer::loadEnvironment(const image::HdrImage& panorama) {
    ENCORE_TRY(mLighting->loadEnvironment(panorama));
    return mContext->checkNoErrors("Loading an environment");
}

Result<void> Renderer::updateLight(std::size_t lightInstance, const scene::Light& light,
                                   const scene::LightInstance& placed) {
    return mLighting->updateLight(lightInstance, light, placed);
}

void Renderer::toneMapScene() {
    if (!mToneMapper) {
        return;
    }
    wgpu::CommandEncoder commands = mContext->device().CreateCommandEncoder();
    mToneMapper->encode(commands, mTarget);
    wgpu::CommandBuffer buffer = commands.Finish();
    mContext->queue().Submit(1, &buffer);
}

Result<std::vector<float>> Renderer::readHdrImage() {
    if (!mTarget.hdr()) {
        return makeError(ErrorCode::InvalidArgument, "The render target has no HDR colour.");
    }
    return gpu::readTextureRgba16Float(*mContext, mTarget.sceneTexture());
}

Result<image::ImageRgba8> Renderer::readImage() {
    auto image = gpu::readTexture(*mContext, mTarget.colorTexture());
    if (!image) {
        // A lost device fails the read back; say so rather than how mapping failed.
        ENCORE_TRY(mContext->checkNoErrors("Rendering"));
        return image.error();
    }
    ENCORE_TRY(mContext->checkNoErrors("Rendering"));
    return image;
}

}  // namespace encore::render
