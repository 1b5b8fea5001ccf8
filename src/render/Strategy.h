#pragma once

// A strategy is one step of the case study's path from a naive glTF renderer to an efficient one.
// Each records a frame's draws from the GPU scene (GpuScene: geometry, instances, materials,
// animation, uploaded once) through a RenderEncoder, so every step can be selected, counted and
// compared in one binary. A strategy owns only its recording structures: the pipelines it picks,
// draw groups, bundles, indirect arguments and culling buffers, and what is its very point
// (naive's buffer and bind group per node).

#include <webgpu/webgpu_cpp.h>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "encore/core/Result.h"
#include "encore/render/Camera.h"
#include "encore/render/RendererOptions.h"
#include "encore/render/StrategyKind.h"
#include "encore/scene/SceneData.h"
#include "gpu/GpuTimer.h"
#include "render/InstanceTransformTargets.h"
#include "render/RenderEncoder.h"
#include "render/RenderSetup.h"

namespace encore::render {

// Which part of a frame a render pass draws. Strategies that cull against the depth drawn so
// far (two-phase occlusion culling) split a frame of one view into two passes.
enum class DrawPhase {
    Whole,   // The one pass of the view: everything.
    First,   // What was visible last frame.
    Second,  // What the first pass's depth does not hide and was not drawn yet, then blended.
};

// What a frame's recording may depend on. Only strategies that sort by distance (blended
// geometry) read the camera while recording; all others take it from the frame uniforms.
struct FrameState {
    Camera camera;
    // Every view of the frame, `camera` among them: one, or those of a multi-view frame, which
    // a strategy prepares for once (culling, in beforePass) and then encodes view by view.
    std::span<const Camera> views;
    float timeSeconds = 0.0f;
    gpu::GpuTimer* timer = nullptr;  // Times passes the strategy begins itself (culling).
    // What GPU culling tests instances against when it is not `camera`: a frozen frustum,
    // watched from elsewhere.
    std::optional<Camera> cullingCamera;
    DrawPhase phase = DrawPhase::Whole;
    CullingOptions culling;
    std::uint32_t targetWidth = 0;  // The render target's size in pixels.
    std::uint32_t targetHeight = 0;
    // This scene pass draws straight into the target's resolved texture at one sample, without
    // depth (Strategy::composesResolved).
    bool resolvedPass = false;
    // Set when the renderer composes this frame through Strategy::composeFrame: the background
    // it will pass there (FrameComposition::background), known to beforePass already, and the
    // view of the target that the composition writes: its one-sample scene colour as a
    // write-only storage texture (RenderTarget::sceneStorageView), RGBA8Unorm holding
    // sRGB-encoded bytes, or RGBA16Float with HDR.
    std::optional<wgpu::Color> composedBackground;
    wgpu::TextureView composedView;
    // GPU-evaluated animation writes instance transforms before this frame's passes (CPU
    // animation and edits say so through Strategy::instanceMoved).
    bool transformsAnimated = false;
};

// Where a strategy that composes the frame in compute (Strategy::composesFrame) writes it.
struct FrameComposition {
    // What a pixel nothing covers holds: the scene pass's clear colour (linear).
    wgpu::Color background{0.0, 0.0, 0.0, 0.0};
    const wgpu::PassTimestampWrites* timestampWrites = nullptr;  // For the composing pass.
};

class GpuCuller;
class GpuScene;

// Where a strategy that decides on the GPU what to draw leaves the last frame's triangle counts:
// u32 words of a CopySrc buffer, which Renderer::setTriangleCounting copies every frame.
struct GpuTriangleCounts {
    wgpu::Buffer buffer;
    std::uint64_t hardwareOffset = 0;            // Triangles sent to the hardware rasteriser.
    std::optional<std::uint64_t> computeOffset;  // Triangles rasterised in compute (visibility).
    std::uint64_t candidates = 0;  // The triangles of a view it chooses among (CPU-known).
};

class Strategy {
  public:
    virtual ~Strategy() = default;
    virtual StrategyKind kind() const = 0;

    // Creates the recording structures for `scene`, which (like `setup`) must outlive the
    // strategy.
    virtual Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) = 0;

    // Brings the recording structures up to date after the GPU scene's generation changed (a
    // replaced bind group: a material that gained textures needs other pipelines). Bundles
    // notice the generation themselves before their next replay.
    virtual Result<void> refresh() { return {}; }

    // Work before the frame's render pass: GPU work in `commands` (culling compute passes) and
    // CPU bookkeeping (re-recording bundles whose draw sequence changed).
    virtual void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
        (void)commands;
        (void)frame;
    }

    // Whether this frame (of one view) is drawn in two passes: beforePass, encode() with
    // DrawPhase::First, betweenPhases() with the first pass's depth, encode() with
    // DrawPhase::Second. Asked before beforePass; false: one pass, DrawPhase::Whole.
    virtual bool drawsInTwoPhases(const FrameState& frame) const {
        (void)frame;
        return false;
    }
    // Between the two passes of a two-phase frame: GPU work that reads the first pass's depth.
    virtual void betweenPhases(const wgpu::CommandEncoder& commands,
                               const FrameState& frame,
                               const wgpu::Texture& depth) {
        (void)commands;
        (void)frame;
        (void)depth;
    }

    // Records one frame's draws. Sets every piece of state it uses (group 0 included), so the
    // same code can record into a render bundle.
    virtual void encode(RenderEncoder& encoder, const FrameState& frame) const = 0;

    // Whether, on a multisampled target, the scene passes need nothing but what encode() draws
    // from the strategy's own per-sample data, already averaged per pixel: then the renderer
    // draws them at one sample straight into the target's resolved texture, without depth
    // (FrameState::resolvedPass), and skips the multisampled target, its clears and its resolve
    // (on the H100's few graphics units those cost about four times a one-sample pass).
    virtual bool composesResolved() const { return false; }

    // Whether the strategy writes every pixel of the frame itself in compute (composeFrame),
    // so that the renderer records no scene render pass at all. Asked only for frames the
    // renderer could compose so: one phase, no transmission pass, no pass images, and a plain
    // background colour (an environment is drawn by a render pass).
    virtual bool composesFrame(const FrameState& frame) const {
        (void)frame;
        return false;
    }
    // Records the frame's composition after beforePass(): every pixel of `frame.composedView`
    // (the target's one-sample scene colour) written, uncovered ones with `target.background`.
    virtual void composeFrame(const wgpu::CommandEncoder& commands,
                              const FrameState& frame,
                              const FrameComposition& target) {
        (void)commands;
        (void)frame;
        (void)target;
    }

    // KHR_materials_transmission: whether encode() leaves out surfaces with transmission, for
    // encodeTransmission() to draw in a pass of their own once the Renderer has copied the scene
    // drawn so far (render/TransmissionPass.h). False (the default) when the scene has none, and
    // in strategies that shade no materials (which draw every surface alike).
    virtual bool drawsTransmission() const { return false; }
    // Records the transmissive surfaces into the transmission pass of `frame`'s view (called
    // only when drawsTransmission()); as encode(), it sets every piece of state it uses.
    virtual void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const {
        (void)encoder;
        (void)frame;
    }

    // Strategies that keep instance transforms of their own (the per-node uniforms of naive,
    // layouts and pipeline-cache) rewrite them: the GPU scene's are written already. Data in
    // buffers only, so recorded bundles stay valid.
    virtual void instanceMoved(std::size_t instance, const glm::mat4& world) {
        (void)instance;
        (void)world;
    }
    // Where the transforms this strategy draws with live, for GPU-evaluated animation
    // (GpuAnimation), which writes the animated ones there.
    virtual InstanceTransformTargets instanceTransformTargets() const = 0;

    // Whether the strategy can draw into a target of `width` x `height` (after prepare()):
    // strategies whose buffers grow with the target (visibility) say here, with an error naming
    // the device limit, when they would exceed it. The Renderer asks on prepare and resize.
    virtual Result<void> checkTarget(std::uint32_t width, std::uint32_t height) const {
        (void)width;
        (void)height;
        return {};
    }

    // What the strategy's render bundles contain (zero for strategies that record directly),
    // and how many bundles it has recorded since prepare().
    virtual DrawCounters bundleContents() const { return {}; }
    virtual std::uint64_t bundlesRecorded() const { return 0; }
    // The GPU culling state, for tests and tools; nullptr when the strategy does not cull.
    virtual const GpuCuller* culler() const { return nullptr; }
    // The GPU's triangle counts of the last frame; by default the culler's (none without one).
    virtual std::optional<GpuTriangleCounts> gpuTriangleCounts() const;
};

// With `bundle`, the strategy that draws `kind`'s frame from render bundles (see bundledKind).
std::unique_ptr<Strategy> createStrategy(StrategyKind kind, bool bundle = false);

}  // namespace encore::render
