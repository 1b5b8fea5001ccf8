#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "gpu/BindingResource.h"
#include "render/FramePasses.h"
#include "render/Strategy.h"
#include "render/culling/DepthPyramid.h"
#include "render/strategies/MaterialDrawGroups.h"
#include "render/visibility/VisibilityPipelines.h"
#include "render/visibility/VisibilityTables.h"
#include "render/visibility/VisibilityTarget.h"
#include "render/visibility/VisibilityWorkBuffers.h"

namespace encore::render {

class VisibilityPhasePasses;

// A visibility buffer rasterised in compute (docs/visibility.md). Before the frame's render
// pass, for each view: a compute pass culls items (instance x primitive) against the frustum,
// picks each one's level of detail as GPU culling does, and lists the level's units of 256
// triangles; a compute raster writes each small triangle's
// (depth, id) into a 64-bit-per-pixel storage buffer with atomicStoreMax; triangles that cross
// the near or far plane or span more than maxComputePixels go to one indirect hardware draw whose
// fragments do the same atomic; compute passes then sort the covered pixels into bins by
// material and shade each bin (the PBR code of mesh.wgsl) into a colour texture, once for all
// the views of a frame (a multi-view frame also culls once: docs/visibility.md, "In batches").
// In the render
// pass a fullscreen triangle copies colour and depth of covered samples, and what the compute path
// does not take (MASK, BLEND, skinned or morphed primitives) is drawn as `materials` draws it.
// With occlusion culling (CullingOptions, frames of one view) the cull and raster run twice:
// first the items visible last frame, then, against a depth pyramid of the visibility buffer,
// the other items in the frustum that it does not hide (docs/visibility.md). Needs the
// AtomicVec2uMinMax feature; prepare() fails naming it otherwise.
class VisibilityStrategy final : public Strategy, public FramePasses {
  public:
    // Bounds of the compute raster's triangle sizes, pixels each way: one thread covers those
    // up to computeRasterPixels, a workgroup in tiles those up to workgroupRasterPixels, the
    // hardware larger ones. The fixed-point edge functions, relative to the triangle's first
    // pixel, stay within 32 bits up to 112 pixels and are evaluated in 64 bits beyond; at most
    // 8192 pixels, within which the 64-bit products' factors stay below 2^24.
    static constexpr float kMaxComputePixels = 64.0f;
    static constexpr float kDefaultComputePixels = CullingOptions{}.computeRasterPixels;
    static constexpr float kMaxWorkgroupPixels = 8192.0f;
    // At the largest workgroupRasterPixels (the default) the compute raster takes every
    // triangle: those crossing the near or far plane, or spanning more than it, or that find the
    // workgroup raster's lists full, are clipped and covered by sixteen workgroups each, and the
    // hardware raster pass is not encoded, nor its depth attachment made (fewer passes: the CPU
    // frame).
    static bool computeTakesAll(const CullingOptions& culling) {
        return culling.workgroupRasterPixels >= kMaxWorkgroupPixels;
    }

    // Gives the scene-sized buffers back to the lane's pool (RenderSetup::resources).
    ~VisibilityStrategy() override;

    StrategyKind kind() const override { return StrategyKind::Visibility; }
    Result<void> prepare(const RenderSetup& setup, const GpuScene& scene) override;
    // Builds the tables again when another material variant is selected (the records follow
    // GpuScene::materialOf); regroups the shading bins when a material's textures changed
    // (MaterialBins.h).
    Result<void> refresh() override;
    void beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) override;
    // The items' world spheres are stale (the next frame tests with the matrices).
    void instanceMoved(std::size_t instance, const glm::mat4& world) override {
        (void)instance;
        (void)world;
        mTransformsMoved = true;
    }
    // The last group's shading bins (every view of a frame of up to VisibilityTarget::kSlotViews;
    // CopySrc, tables().binCount records of kBinRecordBytes, each starting with its count of
    // 8x8 tiles listed: one per tile where a sample's triangle is in the bin).
    static constexpr std::uint64_t kBinRecordBytes = 256;
    const wgpu::Buffer& bins() const { return mWork->bins; }
    // The last frame's shaded colour: RGBA16Float, a layer per sample, each distinct triangle of
    // a pixel in the layer of the first sample it covers (CopySrc, for tests).
    const wgpu::Texture& shadedColour() const { return mTarget->shaded; }
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mDraws.scene().instances().transformTargets();
    }

    // Those of the first view; MASK, BLEND, skinned and morphed geometry drawn directly is
    // counted with the frame's direct draws (DrawCounters), not here.
    StrategyReport report() const override;

    FramePasses* framePasses() override { return this; }
    // At four samples, when nothing is drawn after the composite: it averages each pixel's
    // samples itself (visibility_composite.wgsl's pixelMain).
    bool composesResolved() const override {
        return mSetup && mSetup->sampleCount > 1 && !drawsAfter();
    }
    // With nothing drawn after the composite, its work is done in compute for every pixel,
    // straight into the target through a storage view (visibility_composite.wgsl's
    // composeMain): no render pass, whose fragments the H100 runs on its few graphics units.
    bool composesFrame(const FrameState& frame) const override;
    void composeFrame(const wgpu::CommandEncoder& commands,
                      const FrameState& frame,
                      const FrameComposition& target) override;
    // Transmissive surfaces are left to the hardware path, as blended ones are, and drawn in
    // the transmission pass.
    bool drawsTransmission() const override { return !mDraws.transmissive().empty(); }
    void encodeTransmission(RenderEncoder& encoder, const FrameState& frame) const override {
        (void)frame;
        mDraws.setSharedBindGroups(encoder);
        mDraws.encodeTransmissive(encoder);
    }
    // A multisampled target has four visibility samples per pixel at the hardware's 4x
    // positions (docs/visibility.md). The visibility buffer (8 bytes per sample) must fit
    // maxStorageBufferBindingSize, the shaded colour (a texel per sample: twice the target's
    // size each way at 4 samples) maxTextureDimension2D.
    Result<void> checkTarget(std::uint32_t width, std::uint32_t height) const override;

    const VisibilityTables& tables() const { return mTables; }
    // The last frame's visibility buffer: per sample (pixel-major), the triangle's id and the
    // complement of its depth's bits; zero where nothing was drawn (CopySrc, for tests).
    const wgpu::Buffer& visibilityBuffer() const { return mTarget->visibility; }
    // Per view of the last frame, two words from rasterCountsOffset(view) of rasterCounts():
    // triangles rasterised in compute, then triangles drawn by the hardware path (CopySrc, for
    // read-back). A frame of one view leaves them in its counters, where the next frame resets
    // them; a frame of several copies each view's out before the next view's raster.
    const wgpu::Buffer& rasterCounts() const;
    std::uint64_t rasterCountsOffset(std::size_t view) const;
    std::size_t lastViewCount() const { return mLastViewCount; }
    // The last view's counters (visibility_counters.wgsl; CopySrc): at kListedTrianglesOffset,
    // the triangles of the levels its cull listed (GPU culling's count of drawn triangles).
    static constexpr std::uint64_t kListedTrianglesOffset = 8;
    // At kCulledTrianglesOffset, the triangles of the clusters the raster passes culled (listed,
    // never rasterised: outside the frustum, facing away, or hidden in the second phase).
    static constexpr std::uint64_t kCulledTrianglesOffset = 48;
    const wgpu::Buffer& counters() const { return mCounters; }
    // Whether the last frame culled in two phases, and the pyramid it built (tests).
    bool lastFrameOccluded() const { return mOcclusion; }
    const DepthPyramid& depthPyramid() const { return mTarget->pyramid; }
    // The scene-sized working buffers (tests: kept ones are grown, never made smaller).
    const VisibilityWorkBuffers& workBuffers() const { return *mWork; }
    // Makes the workgroup raster's block list hold at most `blocks` entries until the next
    // prepare (tests: a full list, whose triangles are listed whole).
    void limitWorkgroupBlocks(std::uint32_t blocks) {
        mWorkgroupBlocks = std::min(mWorkgroupBlocks, std::max(blocks, 1u));
    }

  private:
    // Whether the hardware draws anything after the composite (MASK, BLEND, skinned, morphed
    // or transmissive geometry), which then depth-tests against each sample's depth.
    bool drawsAfter() const {
        return !mDraws.opaque().empty() || !mDraws.blended().empty() ||
               !mDraws.transmissive().empty();
    }
    void ensureTarget(std::uint32_t width, std::uint32_t height, std::size_t views);
    void createBindGroups();
    // The binning's and the shading's resources shared by their groups, composed or not.
    std::vector<gpu::BindingResource> binResources() const;
    std::vector<gpu::BindingResource> shadeResources() const;
    // The frame's view of the target for `background`, and the groups over it.
    void ensureComposedShading(const wgpu::TextureView& view, const wgpu::Color& background);
    // A multi-view frame's one cull, before its views (each view's raster starts from the
    // counters it leaves).
    void encodeCull(const wgpu::CommandEncoder& commands, const FrameState& frame) const;
    void dispatchItems(const wgpu::ComputePassEncoder& pass,
                       const wgpu::ComputePipeline& cull) const;
    // The visibility buffer cleared, at the start of the frame's first compute pass.
    void dispatchClear(const wgpu::ComputePassEncoder& pass) const;
    // Culls (unless `culled`) and rasterises one view.
    void encodeView(const wgpu::CommandEncoder& commands,
                    const FrameState& frame,
                    std::size_t view,
                    std::uint32_t viewWidth,
                    bool culled);
    // Bins and shades the views from `firstView` (at most VisibilityTarget::kSlotViews of them,
    // `groupWidth` pixels together) at once: their tiles binned round by round with the
    // parameters of the slots from `firstBinSlot` (one per round of kRoundBins), one shading
    // dispatch per bin; `views`: the frame's (VisibilityPipelines::shading reads one view's
    // parameters from their bindings).
    void encodeShading(const wgpu::CommandEncoder& commands,
                       const FrameState& frame,
                       std::size_t views,
                       std::size_t firstView,
                       std::size_t firstBinSlot,
                       std::uint32_t groupWidth) const;
    // A scene of one shading bin is not binned: its dispatch shades every tile, as the bin's
    // record says (written each frame, since a frame of more bins clears the records).
    bool shadesEveryTile() const { return mTables.bins.size() == 1; }
    void writeEveryTileRecord() const;
    // The shading dispatch of `bin`, its view slots from `slotsOffset`.
    void shadeBin(const wgpu::ComputePassEncoder& pass,
                  std::uint32_t bin,
                  std::size_t views,
                  std::uint32_t slotsOffset) const;
    // The raster dispatches of the units listed so far in this phase: grids of a fixed size
    // that stride over the lists (visibility_raster.wgsl says why not indirect dispatches).
    // Under a GPU timer, each dispatch in a pass of its own (VisibilityPhasePasses).
    void encodeRaster(VisibilityPhasePasses& passes,
                      std::uint32_t paramsOffset,
                      bool secondPhase) const;
    // The hardware list of this phase, drawn into the visibility buffer (the view of
    // `paramsOffset`, `viewWidth` wide).
    void encodeHardwareRaster(const wgpu::CommandEncoder& commands,
                              const FrameState& frame,
                              std::uint32_t paramsOffset,
                              std::uint32_t viewWidth,
                              const char* timerLabel) const;
    // The tables, the draws the compute path leaves and the scene-sized buffers, for the
    // selected material variant.
    Result<void> prepareScene();
    // Copies the materials' uniforms into mMaterialTable where they changed since the last copy.
    void copyMaterialTable(const wgpu::CommandEncoder& commands);
    // A scene-sized buffer holding `bytes`, or zeroed: from RenderSetup::resources when there is
    // a pool (in a batch), else created.
    wgpu::Buffer sceneBuffer(wgpu::BufferUsage usage,
                             std::span<const std::byte> bytes,
                             const char* label) const;
    wgpu::Buffer sceneBuffer(wgpu::BufferUsage usage, std::uint64_t size, const char* label) const;
    void giveBackSceneBuffers();  // Nulls them; to the pool when there is one.
    void writeCullUniform(const FrameState& frame, std::size_t views) const;

    const RenderSetup* mSetup = nullptr;
    const GpuScene* mScene = nullptr;
    MaterialDrawGroups mDraws;  // What the compute path does not draw.
    VisibilityTables mTables;
    std::optional<scene::VariantId> mTablesVariant;  // The variant mTables was built for.

    // Scene-sized buffers.
    wgpu::Buffer mTableBuffer;
    // The materials' uniforms in their shading bins' blocks (MaterialBins.h), copied from the
    // materials' buffer when it changes (mCopiedMaterials: its uniformGeneration then).
    wgpu::Buffer mMaterialTable;
    std::optional<std::uint64_t> mCopiedMaterials;
    wgpu::Buffer mCounters;
    wgpu::Buffer mCulledCounters;         // After a multi-view frame's cull.
    std::uint32_t mWorkgroupBlocks = 0;   // Entries of blocks, then
    std::uint32_t mWorkgroupRecords = 0;  // records of triangles set up.
    std::uint32_t mHardwareCapacity = 0;
    // Workgroups of the striding grids: the raster's (at most the units), the workgroup
    // raster's (at most the listed blocks); each bin's shading grid is the target's
    // (VisibilityTarget::shadeGroups). None exceeds persistentWorkgroups().
    std::uint32_t mRasterGroups = 1;
    std::uint32_t mWorkgroupGroups = 1;
    std::uint32_t mPersistentGroups = 1;  // persistentWorkgroups() of the device.
    wgpu::Buffer mCullUniform;
    wgpu::Buffer mItemVisibility;  // Per item: visible in the last two-phase frame.
    // Per item, its bounds' world sphere (visibility_cull.wgsl), current while mSpheresCurrent;
    // mTransformsMoved: an instance moved since the last frame (instanceMoved).
    wgpu::Buffer mWorldSpheres;
    bool mSpheresCurrent = false;
    bool mComputeSpheres = false;  // This frame computes them, in its first pass.
    bool mTransformsMoved = false;

    wgpu::Buffer mGeometry;  // The first shared geometry buffer, or a placeholder.
    std::uint64_t mGeometryBytes = 0;

    // Scene-independent pipelines, target-sized resources and the (grown) working buffers: the
    // renderer's (RenderSetup::keptObjects), or else this strategy's own.
    VisibilityPipelines* mPipelines = nullptr;  // Makes shading pipelines on first use.
    std::unique_ptr<VisibilityPipelines> mOwnPipelines;
    VisibilityTarget* mTarget = nullptr;
    std::unique_ptr<VisibilityTarget> mOwnTarget;
    VisibilityWorkBuffers* mWork = nullptr;
    std::unique_ptr<VisibilityWorkBuffers> mOwnWork;
    bool mOcclusion = false;  // This frame culls in two phases.
    std::size_t mLastViewCount = 0;

    // Over the scene's buffers and the target's: made on the first frame and whenever the
    // target's resources are made again.
    wgpu::BindGroup mClearGroup;
    wgpu::BindGroup mCullGroup;
    wgpu::BindGroup mRasterGroup;
    wgpu::BindGroup mHardwareGroup;
    wgpu::BindGroup mBinGroup;
    wgpu::BindGroup mShadeGroup;
    wgpu::BindGroup mCompositeGroup;
    wgpu::BindGroup mComposeGroup;  // Made with the target's view (FrameComposition::view).
    // This frame shades into the composed frame (one sample, composed in compute), through
    // these groups (made with the target's view).
    bool mComposedShading = false;
    wgpu::BindGroup mBinComposedGroup;
    wgpu::BindGroup mShadeComposedGroup;
};

}  // namespace encore::render
