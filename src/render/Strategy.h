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
    // depth (FramePasses::composesResolved).
    bool resolvedPass = false;
    // Set when the renderer composes this frame through FramePasses::composeFrame: the background
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

// What a strategy tells about itself, for stats, tests and tools.
struct StrategyReport {
    // What its render bundles contain (zero for strategies that record directly), and how many
    // bundles it has recorded since prepare().
    DrawCounters bundleContents;
    std::uint64_t bundlesRecorded = 0;
    // The GPU culling state; nullptr when the strategy does not cull with GpuCuller.
    const GpuCuller* culler = nullptr;
    // The GPU's triangle counts of the last frame; none when the GPU chooses nothing.
    std::optional<GpuTriangleCounts> gpuTriangleCounts;
};

class FramePasses;

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

    // Records one frame's draws. Sets every piece of state it uses (group 0 included), so the
    // same code can record into a render bundle.
    virtual void encode(RenderEncoder& encoder, const FrameState& frame) const = 0;

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

    // Bundles, culling state and GPU triangle counts (StrategyReport); nothing by default.
    virtual StrategyReport report() const { return {}; }

    // The passes of a frame beyond encode()'s one scene pass (FramePasses.h: two phases,
    // transmission, composition in compute), for the strategies that draw some; nullptr (the
    // default) for those that draw one pass.
    virtual FramePasses* framePasses() { return nullptr; }
    const FramePasses* framePasses() const { return const_cast<Strategy*>(this)->framePasses(); }
};

}  // namespace encore::render
