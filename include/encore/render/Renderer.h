#pragma once

// Renderer draws a SceneData with one strategy into an offscreen RenderTarget: the face of
// Encore's rendering. It is created on a gpu::Context with RendererOptions, prepares a scene for
// a strategy (StrategyKind), then renders frames from cameras and reads them back. Every change
// after prepare() (instances, materials, lighting, tone mapping, animation, variants, culling)
// goes through buffers, so the strategy's recorded bundles stay valid. RendererStats says what it
// did; FrameResult what each frame recorded and how long it took.
//
// What it holds (the strategy, the GPU scene, pipelines and bind groups) is internal to the
// library (src/render/renderer/RendererCore.h).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/image/HdrImage.h"
#include "encore/image/ImageCodec.h"
#include "encore/render/Camera.h"
#include "encore/render/RenderTarget.h"
#include "encore/render/RendererOptions.h"
#include "encore/render/RendererStats.h"
#include "encore/render/StrategyKind.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"

namespace encore::render {

class RendererCore;

// Asks `options` for the device features the visibility strategy uses where the adapter has
// them (64-bit atomic min/max in storage buffers); without them that strategy's prepare() fails
// and every other strategy renders as before.
void requestVisibilityFeatures(gpu::ContextOptions& options);

class Renderer {
  public:
    // The context must outlive the renderer.
    static Result<Renderer> create(gpu::Context& context, const RendererOptions& options);

    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    ~Renderer();

    // With RendererOptions::keepPipelines: creates now what strategy `kind` keeps from one
    // prepare to the next (the visibility strategy's pipelines), so that the first prepare does
    // not wait for them. Nothing for other strategies, or where the device lacks what `kind`
    // needs (prepare says so).
    Result<void> createKeptObjects(StrategyKind kind);

    // Prepares `scene` (which must outlive the renderer, or the next prepare()/releaseScene())
    // for drawing with `kind`, replacing any previous scene or strategy; with `bundle`, the frame
    // is drawn from render bundles. Fails on any WebGPU error raised while preparing.
    Result<void> prepare(const scene::SceneData& scene, StrategyKind kind, bool bundle = false);
    // Draws the prepared scene with another strategy: only the strategy's recording structures
    // are made again; the scene on the GPU, with every edit made through it, stays as it is.
    Result<void> setStrategy(StrategyKind kind, bool bundle = false);
    // Forgets the prepared scene and frees what was made for it, keeping what serves any scene
    // (target, environment, kept pipelines). Frames then draw only the background until the next
    // prepare().
    void releaseScene();
    // Whether the prepared strategy draws from render bundles (a bundled kind, or `bundle`).
    bool bundled() const;
    const scene::SceneData* scene() const;

    // GPU culling tests against `camera` instead of the frame's camera from now on (nullopt:
    // the frame's camera again): a frozen frustum that can be watched from outside.
    void setCullingCamera(std::optional<Camera> camera);
    const std::optional<Camera>& cullingCamera() const;
    // Occlusion culling and levels of detail of the GPU-culling strategies, from the next frame.
    void setCullingOptions(const CullingOptions& culling);
    const CullingOptions& cullingOptions() const;

    // Updates the frame uniforms, records and submits one frame.
    FrameResult renderFrame(const Camera& camera, float timeSeconds = 0.0f);
    // Renders the same scene from several cameras side by side, each view a vertical strip of
    // the target (cameras should use the strip's aspect). Bundle strategies replay one bundle
    // per view; only the camera buffer changes between views.
    FrameResult renderViews(std::span<const Camera> cameras, float timeSeconds = 0.0f);

    // Gives the target a new size, keeping its formats and sample count; the prepared strategy
    // (pipelines and recorded bundles) stays as it is.
    Result<void> resize(std::uint32_t width, std::uint32_t height);

    // Dynamic content, through buffers (bundles stay valid). `instance` indexes
    // SceneData::instances; the world matrix replaces that instance's.
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world);

    // Animation, evaluated on the CPU (scene::AnimationPlayer) or on the GPU
    // (AnimationEvaluation::Gpu: compute passes at the start of the next frame), written into
    // the same buffers either way. Every animation is selected after prepare(); selectAnimation
    // picks one by index or name (scene::findAnimation), or all again with an empty string.
    // Switching evaluation keeps the prepared scene and strategy; the next setAnimationTime
    // renders the same pose either way.
    Result<void> setAnimationEvaluation(AnimationEvaluation evaluation);
    AnimationEvaluation animationEvaluation() const;
    Result<void> selectAnimation(std::string_view nameOrIndex);
    Result<void> setAnimationTime(double seconds);
    // Times past an animation's end: held at its last pose (Clamp, the default) or wrapped
    // around its duration (Loop). Kept across prepare() and device loss.
    void setPlaybackMode(scene::PlaybackMode mode);
    scene::PlaybackMode playbackMode() const;
    // What the last setAnimationTime() did.
    const AnimationFrameStats& animationStats() const;
    // The CPU evaluation's player (at the rest pose under GPU evaluation); null before prepare().
    const scene::AnimationPlayer* animationPlayer() const;

    Result<void> updateMaterial(scene::MaterialId material, const scene::Material& value);
    // Replaces a material's base colour image (materials-based strategies); recorded bundles
    // that used the old texture are re-recorded before they execute again.
    Result<void> replaceBaseColorImage(scene::MaterialId material, const scene::Image& image);

    // KHR_materials_variants: draws every primitive with the material `variant` maps it to
    // (nullopt: the default materials; scene::resolveVariant finds one by name or index). Only
    // material bindings change: nothing is uploaded again. Holds until the next prepare().
    Result<void> selectVariant(std::optional<scene::VariantId> variant);
    std::optional<scene::VariantId> variant() const;

    // Lighting and tone mapping, through buffers and in-place texture writes: recorded bundles
    // stay valid.
    void setLighting(const LightingParameters& parameters);
    const LightingParameters& lighting() const;
    // Fails when asking for a transparent background on a target without HDR.
    Result<void> setToneMapping(const ToneMappingOptions& options);
    const ToneMappingOptions& toneMapping() const;
    // Recomputes the environment maps from `panorama` into the same textures.
    Result<void> loadEnvironment(const image::HdrImage& panorama);
    // The image-based light, to share with another renderer (RendererOptions::environment or
    // setEnvironment): several renderers may light with one.
    std::shared_ptr<Environment> environment() const;
    // Lights with `environment` (null is ignored) from the next prepare(), setStrategy() or
    // releaseScene() on, or at once when no strategy is prepared.
    void setEnvironment(std::shared_ptr<Environment> environment);
    // Rewrites a placed light (an index into SceneData::lightInstances of the prepared scene).
    Result<void> updateLight(std::size_t lightInstance,
                             const scene::Light& light,
                             const scene::LightInstance& placed);

    // Tone maps the target's HDR scene colour into its output now: for callers that record
    // their own passes into target().colorAttachment() (renderFrame does this itself). Nothing
    // to do without HDR.
    void toneMapScene();

    // Triangle counting, for strategies that decide on the GPU what to draw (GPU culling, the
    // visibility buffer): while on, every frame copies the GPU's counts of what it drew into a
    // history on the GPU, without waiting; takeTriangleHistory waits for the GPU and returns
    // one entry per frame since counting began or since the last take (empty when counting is
    // off or the strategy does not decide on the GPU). Turning it on, or prepare(), starts a new
    // history.
    void setTriangleCounting(bool on);
    bool triangleCounting() const;
    Result<std::vector<DrawnTriangles>> takeTriangleHistory();
    // The same, as the total per frame.
    Result<std::vector<std::uint64_t>> takeDrawnTriangles();

    // Waits for the GPU and reads the final image back.
    Result<image::ImageRgba8> readImage();
    // The frame's linear HDR colour before tone mapping (RGBA floats, alpha = coverage).
    Result<std::vector<float>> readHdrImage();
    // A pass image of the last frame (RendererOptions::passTargets; null without): Normal,
    // Albedo and Material as RGBA8UnormSrgb (n * 0.5 + 0.5, the base colour,
    // occlusion/roughness/metallic, straight alpha), DepthAndId as RGBA16Float (depth along the
    // camera axis, id % 256, id / 256, coverage; premultiplied by coverage). CopySrc.
    wgpu::Texture passTexture(PassImage image) const;
    // The same through a view that a compute pass reads the bytes by
    // (RenderTargetOptions::bytesViews): RGBA8Unorm for the 8-bit images, DepthAndId as it is.
    wgpu::TextureView passBytesView(PassImage image) const;

    // After the device was lost (gpu::Context::deviceLost()): asks the context for a new
    // device and rebuilds every GPU resource from CPU data (options, environment, the prepared
    // scene as loaded, strategy, animation selection, playback and time).
    Result<void> recoverFromDeviceLoss();

    const RenderTarget& target() const;
    RendererStats stats() const;
    gpu::Context& context();

  private:
    friend RendererCore& internals(Renderer& renderer);
    friend const RendererCore& internals(const Renderer& renderer);

    Renderer() = default;

    std::unique_ptr<RendererCore> mCore;
};

}  // namespace encore::render
