#pragma once

// A strategy is one step of the case study's path from a naive glTF renderer to an efficient one.
// Each prepares its own GPU resources from SceneData and records a frame's draws through a
// RenderEncoder, so every step can be selected, counted and compared in one binary.

#include <webgpu/webgpu_cpp.h>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/gpu/GpuTimer.h"
#include "encore/render/BindGroupLayouts.h"
#include "encore/render/Camera.h"
#include "encore/render/CullingOptions.h"
#include "encore/render/FrameUniforms.h"
#include "encore/render/InstanceTransformTargets.h"
#include "encore/render/RenderEncoder.h"
#include "encore/scene/SceneData.h"
#include "encore/shaders/ShaderLibrary.h"

namespace encore::render {

enum class StrategyKind {
    // One pipeline per primitive; one uniform buffer + bind group per node; each attribute
    // copied into its own tightly packed vertex buffer and bound to its own slot.
    Naive,
    // Vertex data bound in place: one buffer per bufferView, offsets in setVertexBuffer,
    // interleaved attributes bound once. Still one pipeline per primitive.
    Layouts,
    // Pipelines cached by every pipeline argument; loop pipeline -> primitive -> node.
    PipelineCache,
    // All transforms in one storage buffer; one draw per primitive for all its instances.
    Instancing,
    // glTF materials: base colour factor/texture/sampler, MASK, BLEND (sorted back to front),
    // double-sided culling; loop pipeline -> material -> primitive.
    Materials,
    // The materials frame recorded once into render bundles and replayed with executeBundles;
    // dynamic data changes through buffers.
    Bundles,
    // GPU frustum culling: a compute pass writes indirect instance counts and visible lists;
    // one indirect draw per primitive, recorded directly every frame.
    GpuCulling,
    // GPU culling with the indirect draws recorded once into a render bundle.
    GpuCullingBundles,
};

std::string_view strategyName(StrategyKind kind);
std::optional<StrategyKind> strategyFromName(std::string_view name);
std::span<const StrategyKind> allStrategies();

// The bundling axis. Every strategy can draw its frame from render bundles: `materials` and
// `gpu-culling` have their own bundled kinds (`bundles`, `gpu-culling-bundles`, which also keep
// blended geometry sorted); the others, whose recording does not depend on the camera, are
// recorded once into a bundle by a wrapper. bundledKind names the own bundled kind (a bundled
// kind names itself), directKind the direct kind of a bundled one (nullopt for the others).
std::optional<StrategyKind> bundledKind(StrategyKind kind);
std::optional<StrategyKind> directKind(StrategyKind kind);
bool isBundledKind(StrategyKind kind);
// The kinds whose culling pass chooses what to draw (render::CullingOptions applies to them).
bool cullsOnTheGpu(StrategyKind kind);

// A point on both axes: a strategy, drawn directly or recorded once into render bundles.
// Normalised so that equal frames compare equal: a kind with a bundled kind of its own is
// bundled by naming that kind (`materials` bundled is `bundles`, with bundle false).
struct StrategyChoice {
    StrategyKind kind = StrategyKind::Bundles;
    bool bundle = false;

    static StrategyChoice of(StrategyKind kind, bool bundle);
    bool operator==(const StrategyChoice&) const = default;
};

// The choice's name in reports and on the command line: the kind's name, or for a kind recorded
// by the bundling wrapper "<name>+bundle" (`naive+bundle`).
std::string strategyChoiceName(StrategyChoice choice);
// Reads strategyChoiceName's names back; nullopt for anything else.
std::optional<StrategyChoice> strategyChoiceFromName(std::string_view name);
// `choices`, each followed (with `alsoBundled`) by its bundled form, every distinct choice once
// in first-seen order: the bundling axis of `stats --bundle` and `bench --bundle`.
std::vector<StrategyChoice> withBundlingAxis(std::span<const StrategyChoice> choices,
                                             bool alsoBundled);

class AnimationBuffers;
class MipmapGenerator;
class PipelineCache;
class StagedImages;

// Where Renderer::prepare's time went, in milliseconds. The materials-based strategies fill in
// their parts; other strategies' work counts only in `strategy`.
struct PrepareTimes {
    double release = 0.0;    // Freeing the previous scene (waiting for the GPU first, by default).
    double animation = 0.0;  // Lights, the animation player and its buffers.
    double strategy = 0.0;   // Strategy::prepare, the four parts below included.
    double geometry = 0.0;   // Vertex and index data, uploaded into the shared buffers.
    double instances = 0.0;  // Instance transforms and their bind group.
    double materials = 0.0;  // Textures (upload and mipmaps), samplers, material bind groups.
    // The textures' part of `materials` (MaterialResources::uploadTimes).
    double textureCreation = 0.0;
    double textureWrites = 0.0;
    double mipmaps = 0.0;
    double materialSubmit = 0.0;
    double draws = 0.0;      // Grouping the draws: pipelines (found or created), vertex bindings.
    double checks = 0.0;     // Collecting errors (out-of-memory scope, validation errors).

    double total() const { return release + animation + strategy + checks; }
    PrepareTimes& operator+=(const PrepareTimes& other);
};

// What a strategy's pipelines and bind groups must be compatible with.
struct RenderSetup {
    wgpu::Device device;
    wgpu::Queue queue;
    shaders::ShaderLibrary* shaders = nullptr;
    const BindGroupLayouts* layouts = nullptr;
    const FrameUniforms* frame = nullptr;
    wgpu::TextureFormat colorFormat = wgpu::TextureFormat::RGBA8UnormSrgb;
    wgpu::TextureFormat depthFormat = wgpu::TextureFormat::Depth32Float;
    std::uint32_t sampleCount = 1;
    // gpu::Context::mappingBudget(): strategies that create a buffer and a bind group per node
    // refuse scenes that would exceed it rather than crash the driver.
    std::optional<std::uint64_t> mappingBudget;
    // gpu::Context::limits(): what buffers and textures are sized against.
    gpu::DeviceLimits limits;
    // The images of the scene being prepared, already in staging buffers (Renderer::prepare's
    // `staged`); null: MaterialResources writes them itself.
    StagedImages* stagedImages = nullptr;
    // Render pipelines created through this setup (createMeshPipeline), for stats.
    mutable std::uint64_t pipelinesCreated = 0;
    // The last Renderer::prepare's times; strategies add their parts.
    mutable PrepareTimes prepareTimes;
    // The prepared scene's skinning and morph data, shared by every strategy (owned by the
    // Renderer); null when the scene has none (or for strategies prepared outside a Renderer):
    // primitives are then drawn unanimated, as loaded.
    const AnimationBuffers* animation = nullptr;
    // Pipelines that outlive the prepared strategy (RendererOptions::keepPipelines), owned by
    // the Renderer; null: each strategy caches its own.
    PipelineCache* keptPipelines = nullptr;
    // Fills textures' mip chains, owned by the Renderer so that its pipelines outlive each
    // scene; null: MaterialResources makes one per scene.
    MipmapGenerator* mipmaps = nullptr;
};

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
};

class GpuCuller;

class Strategy {
  public:
    virtual ~Strategy() = default;
    virtual StrategyKind kind() const = 0;

    // Creates the GPU resources for `scene`, which must outlive the strategy.
    virtual Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) = 0;

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
    virtual void betweenPhases(const wgpu::CommandEncoder& commands, const FrameState& frame,
                               const wgpu::Texture& depth) {
        (void)commands;
        (void)frame;
        (void)depth;
    }

    // Records one frame's draws. Sets every piece of state it uses (group 0 included), so the
    // same code can record into a render bundle.
    virtual void encode(RenderEncoder& encoder, const FrameState& frame) const = 0;

    // Dynamic content: these change data in buffers only, so recorded bundles stay valid.
    // `instance` is an index into SceneData::instances.
    virtual Result<void> updateInstance(std::size_t instance, const glm::mat4& world) = 0;
    // Where the strategy keeps instance transforms, for GPU-evaluated animation (GpuAnimation),
    // which writes the animated ones there instead of updateInstance.
    virtual InstanceTransformTargets instanceTransformTargets() const = 0;
    // Strategies without materials ignore material changes (they do not draw them).
    virtual Result<void> updateMaterial(scene::MaterialId material, const scene::Material& value) {
        (void)material;
        (void)value;
        return {};
    }

    // Replaces a material's base colour image; Unsupported for strategies without materials.
    virtual Result<void> replaceBaseColorImage(scene::MaterialId material,
                                               const scene::Image& image) {
        (void)material;
        (void)image;
        return makeError(ErrorCode::Unsupported,
                         "This strategy draws no materials, so it has no textures to replace.");
    }

    // What the strategy's render bundles contain (zero for strategies that record directly),
    // and how many bundles it has recorded since prepare().
    virtual DrawCounters bundleContents() const { return {}; }
    virtual std::uint64_t bundlesRecorded() const { return 0; }
    // The GPU culling state, for tests and tools; nullptr when the strategy does not cull.
    virtual const GpuCuller* culler() const { return nullptr; }
};

// With `bundle`, the strategy that draws `kind`'s frame from render bundles (see bundledKind).
std::unique_ptr<Strategy> createStrategy(StrategyKind kind, bool bundle = false);

// Checks an instance index given to Strategy::updateInstance.
Result<void> checkInstanceIndex(std::size_t instance, std::size_t instanceCount);

}  // namespace encore::render
