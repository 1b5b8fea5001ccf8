#pragma once

// RendererCore is what a Renderer (encore/render/Renderer.h, the public face) holds: it draws a
// SceneData with one strategy into an offscreen RenderTarget. It owns what all strategies share
// (shader library, bind group layouts, frame uniforms, the scene's lighting and environment, tone
// mapping), the prepared scene on the GPU (GpuScene) and the strategy itself. A frame renders the
// scene into the target's sRGB output, the shaders applying the display transform as they shade;
// with an HDR target (RenderTargetOptions::hdr, or a transparent background) it renders linear
// HDR and a tone-mapping pass writes the output.
//
// In-tree code that needs more than the public face (the strategy, the GPU scene, the render
// setup, staged uploads, timers and pools: tests, encore batch, benchmarks, the viewer) reaches it
// through render::internals(renderer).

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/HdrImage.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Camera.h"
#include "encore/render/RenderTarget.h"
#include "encore/render/Renderer.h"
#include "encore/render/RendererOptions.h"
#include "encore/render/RendererStats.h"
#include "encore/scene/AnimationPlayer.h"
#include "gpu/StageTimestamps.h"
#include "render/AnimationBuffers.h"
#include "render/GpuStage.h"
#include "render/Lighting.h"
#include "render/StagedUploads.h"
#include "render/Strategy.h"
#include "render/ToneMapper.h"
#include "render/animation/GpuAnimation.h"

namespace encore::gpu {
class OutOfMemoryScope;
class ResourcePool;
}  // namespace encore::gpu

namespace encore::render {

class GpuScene;
class TriangleHistory;
class TransmissionPass;
class PassTargetTextures;
class SampleIdPass;

class RendererCore {
  public:
    // The context must outlive the renderer.
    static Result<RendererCore> create(gpu::Context& context, const RendererOptions& options);

    RendererCore(RendererCore&&) noexcept;
    RendererCore& operator=(RendererCore&&) noexcept;
    ~RendererCore();

    // With RendererOptions::keepPipelines: creates now what strategy `kind` keeps from one
    // prepare to the next (the visibility strategy's pipelines), so that the first prepare does
    // not wait for them; encore batch calls it while its loaders read the first models. Nothing
    // for other strategies, or where the device lacks what `kind` needs (prepare says so).
    Result<void> createKeptObjects(StrategyKind kind);

    // Prepares `scene` (which must outlive the renderer) for drawing with `kind`, replacing any
    // previous scene or strategy: uploads it into a new GPU scene (GpuScene) and prepares the
    // strategy on it; with `bundle`, the frame is drawn from render bundles (createStrategy).
    // Fails on any WebGPU error raised while preparing. `staged`: the scene's images and
    // geometry already copied into staging buffers (the GPU scene copies from there), used
    // during this call only.
    Result<void> prepare(const scene::SceneData& scene,
                         StrategyKind kind,
                         bool bundle = false,
                         const StagedUploads& staged = {});
    // Draws the prepared scene with another strategy: only the strategy's recording structures
    // are made again; the GPU scene, with every edit made through it, stays as it is.
    Result<void> setStrategy(StrategyKind kind, bool bundle = false);
    // Forgets the prepared scene and frees what was made for it (the strategy's buffers,
    // textures and bundles, the animation), keeping what serves any scene (target, environment,
    // kept pipelines). For a renderer kept after the scene it prepared is gone (encore batch
    // between two runs): it no longer refers to that scene. Frames then draw nothing but the
    // background until the next prepare().
    void releaseScene();
    // Whether the prepared strategy draws from render bundles (a bundled kind, or `bundle`).
    bool bundled() const { return mBundle || isBundledKind(mKind); }
    RendererStats stats() const;
    const scene::SceneData* scene() const { return mScene; }

    // GPU culling tests against `camera` instead of the frame's camera from now on (nullopt:
    // the frame's camera again): a frozen frustum that can be watched from outside.
    void setCullingCamera(std::optional<Camera> camera) { mCullingCamera = camera; }
    const std::optional<Camera>& cullingCamera() const { return mCullingCamera; }
    // Occlusion culling and levels of detail of the GPU-culling strategies, from the next frame.
    void setCullingOptions(const CullingOptions& culling) { mOptions.culling = culling; }
    const CullingOptions& cullingOptions() const { return mOptions.culling; }

    // Updates the frame uniforms, records and submits one frame. With `trace`, every recorded
    // call is also appended there (tests).
    FrameResult renderFrame(const Camera& camera,
                            float timeSeconds = 0.0f,
                            std::vector<RecordedCall>* trace = nullptr);

    // Renders the same scene from several cameras side by side, each view a vertical strip of
    // the target (cameras should use the strip's aspect). Bundle strategies replay one bundle
    // per view; only the camera buffer changes between views.
    FrameResult renderViews(std::span<const Camera> cameras, float timeSeconds = 0.0f);

    // Gives the target a new size, keeping its formats and sample count: the depth, multisample
    // and output textures are created again, while the prepared strategy (its pipelines and
    // recorded bundles, which depend on formats and sample count only) stays as it is.
    Result<void> resize(std::uint32_t width, std::uint32_t height);

    // Dynamic content, through buffers (bundles stay valid). `instance` indexes
    // SceneData::instances; the world matrix replaces that instance's.
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world);

    // Animation, evaluated on the CPU (scene::AnimationPlayer) and uploaded through buffers:
    // changed instance transforms through the strategy's updateInstance, joint matrices and
    // morph weights into the shared AnimationBuffers that skinned and morphed variants read.
    // Every animation is selected after prepare(); selectAnimation picks one by index or name
    // (scene::findAnimation), or all again with an empty string.
    //
    // With AnimationEvaluation::Gpu, setAnimationTime only writes the animations' local times;
    // the next frame's command buffer starts with GpuAnimation's compute passes, which write the
    // same buffers (so animationPlayer() keeps the rest pose). Switching evaluation keeps the
    // prepared scene and strategy; the next setAnimationTime renders the same pose either way.
    Result<void> setAnimationEvaluation(AnimationEvaluation evaluation);
    AnimationEvaluation animationEvaluation() const { return mOptions.animation; }
    const GpuAnimation* gpuAnimation() const { return mGpuAnimation.get(); }
    Result<void> selectAnimation(std::string_view nameOrIndex);
    Result<void> setAnimationTime(double seconds);
    // Times past an animation's end: held at its last pose (Clamp, the default, as `encore render
    // --time` wants) or wrapped around its duration (Loop: the viewer, benchmarks). Kept across
    // prepare() and device loss.
    void setPlaybackMode(scene::PlaybackMode mode);
    scene::PlaybackMode playbackMode() const { return mPlaybackMode; }
    const AnimationFrameStats& animationStats() const { return mAnimationStats; }
    const scene::AnimationPlayer* animationPlayer() const { return mPlayer.get(); }
    const AnimationBuffers* animationBuffers() const;

    Result<void> updateMaterial(scene::MaterialId material, const scene::Material& value);
    // Replaces a material's base colour image (materials-based strategies); recorded bundles
    // that used the old texture are re-recorded before they execute again.
    Result<void> replaceBaseColorImage(scene::MaterialId material, const scene::Image& image);

    // KHR_materials_variants: draws every primitive with the material `variant` maps it to
    // (nullopt: the default materials; scene::resolveVariant finds one by name or index). Only
    // material bindings change: nothing is uploaded again (sceneUploads() and uploadedBytes()
    // stay), the strategy regroups its draws and bundles record again before the next frame.
    // The selection holds until the next prepare() (it survives setStrategy and device loss).
    Result<void> selectVariant(std::optional<scene::VariantId> variant);
    std::optional<scene::VariantId> variant() const;

    // Lighting and tone mapping, through buffers and in-place texture writes: recorded bundles
    // stay valid (tests check bundlesRecorded).
    void setLighting(const LightingParameters& parameters);
    // Fails when asking for a transparent background on a target without HDR.
    Result<void> setToneMapping(const ToneMappingOptions& options);
    const ToneMappingOptions& toneMapping() const { return mOptions.toneMapping; }
    // Recomputes the environment maps from `panorama` into the same textures.
    Result<void> loadEnvironment(const image::HdrImage& panorama);
    // Lights with `environment` (already built; several renderers may share one; null is
    // ignored) from the next prepare(), setStrategy() or releaseScene() on, or at once when no
    // strategy is prepared: a prepared strategy holds the bind group that binds the environment,
    // so it keeps the one it was prepared with. Switching between the preparation of two scenes
    // (encore batch, one environment per model) costs one bind group and no recording.
    void setEnvironment(std::shared_ptr<Environment> environment);
    // Rewrites a placed light (an index into SceneData::lightInstances of the prepared scene).
    Result<void> updateLight(std::size_t lightInstance,
                             const scene::Light& light,
                             const scene::LightInstance& placed);
    const SceneLighting& lighting() const { return *mLighting; }
    std::shared_ptr<Environment> environment() const { return mLighting->sharedEnvironment(); }

    // Tone maps the target's HDR scene colour into its output now: for callers that record
    // their own passes into target().colorAttachment() (renderFrame does this itself). Nothing
    // to do without HDR.
    void toneMapScene();

    // Triangle counting, for strategies that decide on the GPU what to draw (GPU culling, the
    // visibility buffer): while on, every frame copies the GPU's counts of what it drew
    // (StrategyReport::gpuTriangleCounts) into a history on the GPU, without waiting for anything;
    // takeTriangleHistory reads it back later, outside the frames being measured. Turning it on
    // starts a new history; prepare() does too.
    void setTriangleCounting(bool on);
    bool triangleCounting() const { return mTriangleHistory != nullptr; }
    // Waits for the GPU and returns one entry per frame rendered since counting began (or since
    // the last take, which starts a new history); empty when counting is off or the prepared
    // strategy does not decide on the GPU.
    Result<std::vector<DrawnTriangles>> takeTriangleHistory();
    // The same, as the total per frame.
    Result<std::vector<std::uint64_t>> takeDrawnTriangles();

    // Waits for the GPU and reads the final image back.
    Result<image::ImageRgba8> readImage();
    // A pass image of the last frame (RendererOptions::passTargets; null without): Normal,
    // Albedo and Material as RGBA8UnormSrgb (the debug channels' images: n * 0.5 + 0.5, the
    // base colour, occlusion/roughness/metallic, straight alpha), DepthAndId as RGBA16Float
    // (depth along the camera axis, id % 256, id / 256, coverage; premultiplied by coverage).
    // CopySrc, for read-backs.
    wgpu::Texture passTexture(PassImage image) const;
    // The same through a view that a compute pass reads the bytes by (RenderTargetOptions::
    // bytesViews): RGBA8Unorm for the 8-bit images, DepthAndId as it is.
    wgpu::TextureView passBytesView(PassImage image) const;
    // The frame's linear HDR colour before tone mapping (RGBA floats, alpha = coverage); for
    // tests of the shading itself (energy, furnace).
    Result<std::vector<float>> readHdrImage();

    // Times every pass of later frames with `timer` (nullptr: untimed); each frame then waits
    // for its timestamps and reports them in FrameResult::gpuMilliseconds.
    void setGpuTimer(gpu::GpuTimer* timer) { mTimer = timer; }
    // Adds the GPU time of later work to `timestamps` by GpuStage (its stage count at least
    // kGpuStageCount), without waiting for it: the mip generation of prepare(), the scene and
    // tone-mapping passes of frames. nullptr: untimed. The caller flushes. A GPU timer set with
    // setGpuTimer takes the frame's passes instead.
    void setStageTimestamps(gpu::StageTimestamps* timestamps);
    // Takes later scenes' buffers and textures from `pool` and gives them back when they are
    // released (RenderSetup::resources); the pool must outlive this renderer's scenes and belong
    // to its device. nullptr: each scene creates and releases its own.
    void setResourcePool(gpu::ResourcePool* pool);

    // After the device was lost (gpu::Context::deviceLost()): asks the context for a new
    // device and rebuilds every GPU resource from CPU data — the options as last set, the
    // environment's panorama, the prepared scene (as loaded: edits made through update*
    // since prepare() are not replayed), the strategy, and the animation's selection, playback
    // mode and last time. Frames render again afterwards, as they were before the loss.
    Result<void> recoverFromDeviceLoss();

    const RenderTarget& target() const { return mTarget; }
    const RenderSetup& setup() const { return *mSetup; }
    // Where the last prepare()'s time went.
    const PrepareTimes& prepareTimes() const { return mSetup->prepareTimes; }
    const Strategy* strategy() const { return mStrategy.get(); }
    // The prepared scene on the GPU; null before prepare() and after releaseScene().
    const GpuScene* gpuScene() const { return mGpuScene.get(); }
    // How many GPU scenes this renderer built (prepare() and device recovery, never a switch of
    // strategy), and the geometry and texture bytes they uploaded, edits included.
    std::uint64_t sceneUploads() const { return mSceneUploads; }
    std::uint64_t uploadedBytes() const;
    gpu::Context& context() { return *mContext; }

  private:
    RendererCore() = default;
    Result<void> build(const RendererOptions& options);
    Result<void> createGpuAnimation();
    // Makes mPendingEnvironment the lighting's environment, binding it in the frame bind group.
    void applyPendingEnvironment();
    // Creates and prepares the strategy on the GPU scene, then finishes `outOfMemory` (opened
    // by the caller) and collects errors; `what` names it in errors.
    Result<void> prepareStrategy(StrategyKind kind,
                                 bool bundle,
                                 const std::string& what,
                                 gpu::OutOfMemoryScope& outOfMemory);
    // Frees the GPU scene, counting what it uploaded.
    void retireGpuScene();
    // Lets Dawn free what was released (waiting for the GPU first, by default).
    void freeReleasedObjects();
    // What of the player outlives a new player (a device loss, a switch of evaluation): which
    // animations play and how. restorePlayback applies it to the current player and the GPU
    // evaluation.
    struct Playback {
        std::vector<scene::AnimationId> selection;
        scene::PlaybackMode mode{};
    };
    Playback playback() const;
    Result<void> restorePlayback(const Playback& playback);
    // The timestamp writes of a pass of `stage`: the GPU timer's, else the stage timestamps'.
    const wgpu::PassTimestampWrites* timestampWrites(GpuStage stage,
                                                     std::string_view label = "pass");
    // Binds the GPU scene's transmission background (or none) and makes the copy's pass.
    Result<void> prepareTransmission();
    FrameResult renderPasses(std::span<const Camera> cameras,
                             float timeSeconds,
                             std::vector<RecordedCall>* trace);
    // The steps of renderPasses (RendererFrame.cpp): which passes the frame takes, then what
    // its command encoder records: the compute work before the passes, the scene passes (or the
    // strategy's composition), the transmission copy and passes, tone mapping and pass images.
    struct FramePlan;
    FramePlan planFrame(std::span<const Camera> cameras,
                        float timeSeconds,
                        std::vector<RecordedCall>* trace) const;
    void encodeFrame(const wgpu::CommandEncoder& commandEncoder,
                     const FramePlan& plan,
                     FrameResult& result);
    void encodeScenePasses(const wgpu::CommandEncoder& commandEncoder,
                           const FramePlan& plan,
                           FrameResult& result);
    void encodeTransmissionPasses(const wgpu::CommandEncoder& commandEncoder,
                                  const FramePlan& plan,
                                  FrameResult& result);
    // One render pass of `view` in `phase`: its attachments, then drawView.
    void encodeScenePass(const wgpu::CommandEncoder& commandEncoder,
                         const FramePlan& plan,
                         std::size_t view,
                         DrawPhase phase,
                         bool transmissionPass,
                         FrameResult& result);
    // The view's viewport, the environment background and the strategy's draws.
    void drawView(const wgpu::RenderPassEncoder& pass,
                  const FramePlan& plan,
                  std::size_t view,
                  DrawPhase phase,
                  bool transmissionPass,
                  FrameResult& result);

    gpu::Context* mContext = nullptr;
    RendererOptions mOptions;
    RenderTarget mTarget;
    std::unique_ptr<shaders::ShaderLibrary> mShaders;
    std::unique_ptr<BindGroupLayouts> mLayouts;
    std::unique_ptr<SceneLighting> mLighting;          // Before mFrame: its bind group binds these.
    std::shared_ptr<Environment> mPendingEnvironment;  // setEnvironment's, not yet bound.
    std::unique_ptr<FrameUniforms> mFrame;
    std::unique_ptr<ToneMapper> mToneMapper;           // HDR targets only.
    std::unique_ptr<PassTargetTextures> mPassTargets;  // RendererOptions::passTargets only.
    // The ids of frames drawn through a segmentation channel: multisampled HDR targets with
    // RenderTargetOptions::exactIds only.
    std::unique_ptr<SampleIdPass> mSceneIds;
    std::unique_ptr<EnvironmentBackground> mBackground;
    // At one sample without depth, for resolved passes (FramePasses::composesResolved): made on
    // a multisampled target by the first strategy that draws them.
    std::unique_ptr<EnvironmentBackground> mResolvedBackground;
    std::unique_ptr<RenderSetup> mSetup;  // Stable address: strategies keep pointers to it.
    std::unique_ptr<PipelineCache> mKeptPipelines;      // With RendererOptions::keepPipelines.
    std::unique_ptr<KeptStrategyObjects> mKeptObjects;  // Likewise.
    std::unique_ptr<MipmapGenerator> mMipmaps;
    std::unique_ptr<scene::AnimationPlayer> mPlayer;
    std::unique_ptr<GpuScene> mGpuScene;  // Before mStrategy, which records from it.
    // The copy for transmissive surfaces; only while the GPU scene has transmission.
    std::unique_ptr<TransmissionPass> mTransmission;
    std::uint64_t mSceneUploads = 0;
    std::uint64_t mRetiredUploadBytes = 0;  // Of the GPU scenes freed since creation.
    AnimationFrameStats mAnimationStats;
    std::optional<double> mAnimationTime;  // The last setAnimationTime() since prepare().
    scene::PlaybackMode mPlaybackMode = scene::PlaybackMode::Clamp;
    std::unique_ptr<Strategy> mStrategy;
    std::unique_ptr<GpuAnimation> mGpuAnimation;  // After mStrategy: writes its buffers.
    bool mGpuAnimationPending = false;  // Time set since the last frame encoded the passes.
    gpu::GpuTimer* mTimer = nullptr;
    gpu::StageTimestamps* mStageTimestamps = nullptr;
    const scene::SceneData* mScene = nullptr;
    StrategyKind mKind = StrategyKind::Bundles;
    bool mBundle = false;
    std::optional<Camera> mCullingCamera;
    std::unique_ptr<TriangleHistory> mTriangleHistory;  // While counting.
};

// The whole renderer behind a Renderer, for in-tree code (tests, encore batch, benchmarks, the
// viewer): the strategy, the GPU scene, the render setup, staged uploads, timers and pools.
RendererCore& internals(Renderer& renderer);
const RendererCore& internals(const Renderer& renderer);

}  // namespace encore::render
