#include "render/visibility/VisibilityStrategy.h"

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "encore/gpu/DeviceLimits.h"
#include "gpu/BindingResource.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/culling/CullingUniform.h"
#include "render/visibility/KeptStrategyObjects.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::render {

namespace {

using ViewParams = VisibilityViewParams;

constexpr std::uint64_t kCounterBytes = VisibilityPipelines::kCounterBytes;
// The hardware list holds at most this many triangles (16 MiB); past it they are counted as an
// overflow (visibility_raster.wgsl) rather than written.
constexpr std::uint64_t kMaxHardwareTriangles = 4u << 20;
// Blocks of 32x32 pixels a triangle of the workgroup path lists: up to 16 up to 112 pixels
// across, which most are; room for a few targets' worth of larger ones on top.
constexpr std::uint64_t kWorkgroupBlocks = 16;
constexpr std::uint64_t kLargeTriangleBlocks = 64 * 1024;
// Each triangle of the workgroup path is set up once, into a record of 8 entries (64 bytes) of
// the workgroup list that its blocks read; at most this many per phase (32 MiB).
constexpr std::uint64_t kWorkgroupRecordEntries = 8;
constexpr std::uint64_t kMaxWorkgroupRecords = 512 * 1024;

// How many 64-thread workgroups a striding grid may have: enough to fill a large GPU (an H100
// holds 132 SMs x 32 such groups), few on a CPU adapter (lavapipe), where every empty group of
// a bin's grid would cost time of its own.
std::uint32_t persistentWorkgroups(const wgpu::Device& device) {
    wgpu::AdapterInfo info{};
    device.GetAdapterInfo(&info);
    return info.adapterType == wgpu::AdapterType::CPU ? 32 : 4096;
}

// A grid for `work` items (units, triangles, entries of `perGroup` each), within the limit.
std::uint32_t stridingGrid(std::uint64_t work, std::uint32_t perGroup, std::uint32_t limit) {
    return std::clamp<std::uint32_t>(
        std::uint32_t(std::min<std::uint64_t>((work + perGroup - 1) / perGroup, limit)), 1, limit);
}

}  // namespace

Result<void> VisibilityStrategy::prepare(const RenderSetup& setup, const GpuScene& scene) {
    if (!setup.device.HasFeature(kVisibilityFeature)) {
        return makeError(ErrorCode::Unsupported,
                         "The visibility strategy needs the WebGPU feature AtomicVec2uMinMax "
                         "(64-bit atomic min and max, WGSL atomic_vec2u_min_max), which this "
                         "device does not have; Dawn offers it only with its allow_unsafe_apis "
                         "toggle (render::requestVisibilityFeatures).");
    }
    if (setup.sampleCount != 1 && setup.sampleCount != 4) {
        return makeError(ErrorCode::Unsupported,
                         "The visibility strategy renders at 1 or 4 samples per pixel, not " +
                             std::to_string(setup.sampleCount) + ".");
    }
    mSetup = &setup;
    mScene = &scene;
    const wgpu::Device& device = setup.device;

    const auto shared = scene.geometry().sharedBuffers();
    if (shared.empty()) {
        mGeometry =
            gpu::createBuffer(device, wgpu::BufferUsage::Storage, 16, "visibility: no geometry");
        mGeometryBytes = 16;
    } else {
        mGeometry = shared[0];
        mGeometryBytes =
            std::min(mGeometry.GetSize(), setup.limits.maxStorageBufferBindingSize) & ~3ull;
    }
    if (setup.keptObjects) {
        KeptStrategyObjects& kept = *setup.keptObjects;
        if (!kept.visibilityPipelines) {
            ENCORE_TRY_ASSIGN(kept.visibilityPipelines, VisibilityPipelines::create(setup));
        }
        mPipelines = kept.visibilityPipelines.get();
        mTarget = &kept.visibilityTarget;
        mWork = &kept.visibilityWork;
    } else {
        ENCORE_TRY_ASSIGN(mOwnPipelines, VisibilityPipelines::create(setup));
        mOwnTarget = std::make_unique<VisibilityTarget>();
        mOwnWork = std::make_unique<VisibilityWorkBuffers>();
        mPipelines = mOwnPipelines.get();
        mTarget = mOwnTarget.get();
        mWork = mOwnWork.get();
    }
    return prepareScene();
}

Result<void> VisibilityStrategy::prepareScene() {
    const RenderSetup& setup = *mSetup;
    const GpuScene& scene = *mScene;
    const wgpu::Device& device = setup.device;
    mTables = buildVisibilityTables(scene, mGeometryBytes);
    mTablesVariant = scene.variant();
    ENCORE_TRY(mDraws.prepare(setup, scene, [this](scene::MeshId mesh, std::size_t primitive) {
        return !mTables.computePath[mesh.index()][primitive];
    }));

    // From the lane's pool in a batch: a model then creates no buffer once the pool holds those
    // of its sizes (issue 48). CopyDst on each: the pool keeps only what can be written again.
    giveBackSceneBuffers();  // Those of the tables before, when a variant's replace them.
    // CopyDst: refresh() rewrites the bin words of records whose materials regrouped.
    const std::uint32_t noWord = 0;
    const std::span<const std::uint32_t> words =
        mTables.words.empty() ? std::span<const std::uint32_t>(&noWord, 1)
                              : std::span<const std::uint32_t>(mTables.words);
    mTableBuffer = sceneBuffer(wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst,
                               std::as_bytes(words), "visibility tables");
    mMaterialTable =
        sceneBuffer(wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                    mTables.materialBins.tableBytes(), "visibility materials of the shading bins");
    mCopiedMaterials.reset();
    mCulledCounters = sceneBuffer(wgpu::BufferUsage::CopySrc | wgpu::BufferUsage::CopyDst,
                                  kCounterBytes, "visibility counters after the cull");
    mCullUniform = sceneBuffer(wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                               sizeof(CullingUniform), "visibility culling");
    // Zero: nothing was visible before the first frame, whose second phase tests everything.
    mItemVisibility = sceneBuffer(wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst,
                                  std::max<std::uint64_t>(mTables.itemCount, 1) * 4,
                                  "visibility of items last frame");
    mWorldSpheres = sceneBuffer(wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst,
                                std::max<std::uint64_t>(mTables.itemCount, 1) * 16,
                                "visibility world spheres of items");
    mSpheresCurrent = false;
    mHardwareCapacity =
        std::uint32_t(std::clamp<std::uint64_t>(mTables.triangleCount, 1, kMaxHardwareTriangles));
    // A triangle of the workgroup path lists its record and its blocks (visibility_raster.wgsl);
    // past either capacity the hardware draws it.
    mWorkgroupBlocks = std::uint32_t(std::clamp<std::uint64_t>(
        mTables.triangleCount * kWorkgroupBlocks + kLargeTriangleBlocks, 1, kMaxHardwareTriangles));
    mWorkgroupRecords =
        std::uint32_t(std::clamp<std::uint64_t>(mTables.triangleCount, 1, kMaxWorkgroupRecords));
    VisibilityWorkBuffers::Sizes sizes;
    // The scene's unit table, then the list: twice the units of all items (with occlusion, the
    // second phase lists again the items of the first, whose clusters it tests for the next
    // frame: visibility_cull.wgsl).
    sizes.units = (mTables.unitListBase() + std::uint64_t(mTables.unitCount) * 2) * 8;
    sizes.hardwareList = std::uint64_t(mHardwareCapacity) * 4;
    sizes.workgroupList = (mWorkgroupBlocks + mWorkgroupRecords * kWorkgroupRecordEntries) * 8;
    sizes.bins = std::uint64_t(mTables.binCount) * kBinRecordBytes;
    // The counters, then the clusters' visibility (visibility_counters.wgsl), which the copies
    // of kCounterBytes that reset the counters leave as they are (zero after prepare).
    mCounters =
        sceneBuffer(wgpu::BufferUsage::Storage | wgpu::BufferUsage::Indirect |
                        wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                    kCounterBytes + std::max<std::uint64_t>(mTables.clusterVisibilityWords, 1) * 4,
                    "visibility counters");
    const std::uint32_t persistent = persistentWorkgroups(device);
    mPersistentGroups = persistent;
    mRasterGroups = stridingGrid(mTables.unitCount, 1, persistent);
    mWorkgroupGroups = stridingGrid(mWorkgroupBlocks, 1, persistent);
    mWork->ensure(device, sizes);
    if (!mTables.unitTable.empty()) {
        mSetup->queue.WriteBuffer(mWork->units, 0, mTables.unitTable.data(),
                                  mTables.unitTable.size() * 4);
    }
    // Over this scene's buffers: made on the first frame.
    mCullGroup = nullptr;
    return {};
}

Result<void> VisibilityStrategy::checkTarget(std::uint32_t width, std::uint32_t height) const {
    const std::uint32_t samples = mSetup->sampleCount;
    const std::string what = "The visibility strategy at " + std::to_string(width) + "x" +
                             std::to_string(height) + " and " + std::to_string(samples) +
                             (samples == 1 ? " sample" : " samples") +
                             " (fewer samples or a smaller target fit)";
    ENCORE_TRY(gpu::checkStorageBinding(mSetup->limits, std::uint64_t(width) * height * samples * 8,
                                        what + ", its visibility buffer"));
    return {};
}

VisibilityStrategy::~VisibilityStrategy() {
    giveBackSceneBuffers();
}

wgpu::Buffer VisibilityStrategy::sceneBuffer(wgpu::BufferUsage usage,
                                             std::span<const std::byte> bytes,
                                             const char* label) const {
    const std::span<const std::uint8_t> data(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                             bytes.size());
    return gpu::bufferWithData(mSetup->resources, mSetup->device, mSetup->queue, usage, data,
                               label);
}

wgpu::Buffer VisibilityStrategy::sceneBuffer(wgpu::BufferUsage usage,
                                             std::uint64_t size,
                                             const char* label) const {
    if (gpu::ResourcePool* pool = mSetup->resources) {
        // A kept buffer holds its last scene's values; a created one is zeroed: so is this.
        const std::vector<std::uint8_t> zeros(size, 0);
        return pool->bufferWithData(mSetup->queue, usage, zeros, label);
    }
    return gpu::createBuffer(mSetup->device, usage, size, label);
}

void VisibilityStrategy::giveBackSceneBuffers() {
    gpu::ResourcePool* pool = mSetup ? mSetup->resources : nullptr;
    for (wgpu::Buffer* buffer : {&mTableBuffer, &mMaterialTable, &mCounters, &mCulledCounters,
                                 &mCullUniform, &mItemVisibility, &mWorldSpheres}) {
        if (pool && *buffer) {
            pool->giveBack(std::move(*buffer));
        }
        *buffer = nullptr;
    }
}

Result<void> VisibilityStrategy::refresh() {
    if (mTablesVariant != mScene->variant()) {
        // Other materials: other records (bins, attributes read, tangents) and, where a variant
        // blends, other draws for the hardware path.
        return prepareScene();
    }
    ENCORE_TRY(mDraws.refresh());
    MaterialBins regrouped(mScene->materials());
    if (regrouped == mTables.materialBins) {
        return {};
    }
    // A material's textures were replaced: it leaves (or joins) the bins of others. Each bin
    // word changed goes to the GPU's tables; the uniforms move to their new slots.
    for (const std::uint32_t word : assignShadingBins(mTables, std::move(regrouped))) {
        mSetup->queue.WriteBuffer(mTableBuffer, std::uint64_t(word) * 4, &mTables.words[word], 4);
    }
    mCopiedMaterials.reset();
    return {};
}

void VisibilityStrategy::ensureTarget(std::uint32_t width,
                                      std::uint32_t height,
                                      std::size_t views) {
    const bool remade =
        mTarget->ensure(*mSetup, width, height, views, mTables.binCount, mPersistentGroups);
    if (remade || !mCullGroup) {
        createBindGroups();
    }
}

void VisibilityStrategy::createBindGroups() {
    const wgpu::Device& device = mSetup->device;
    const VisibilityPipelines& p = *mPipelines;
    const VisibilityTarget& target = *mTarget;
    const wgpu::Buffer& instances = mScene->instances().buffer();
    const gpu::BindingResource params(0, target.params, 0, sizeof(ViewParams));
    mClearGroup =
        gpu::makeBindGroup(device, p.clearLayout, {{0, target.visibility}}, "visibility clear");
    mCullGroup = gpu::makeBindGroup(device, p.cullLayout,
                                    {params,
                                     {2, instances},
                                     {3, mTableBuffer},
                                     {4, mWork->units},
                                     {5, mCounters},
                                     {10, mCullUniform},
                                     {11, mItemVisibility},
                                     {13, mWorldSpheres},
                                     {12, target.pyramid.view()}},
                                    "visibility culling");
    const gpu::BindingResource geometry(1, mGeometry, 0, mGeometryBytes);
    mRasterGroup = gpu::makeBindGroup(device, p.rasterLayout,
                                      {params,
                                       geometry,
                                       {2, instances},
                                       {3, mTableBuffer},
                                       {4, mWork->units},
                                       {5, mCounters},
                                       {6, mWork->hardwareList},
                                       {7, target.visibility},
                                       {9, mWork->workgroupList},
                                       {10, mCullUniform},
                                       {12, target.pyramid.view()}},
                                      "visibility raster");
    mHardwareGroup = gpu::makeBindGroup(device, p.hardwareLayout,
                                        {params,
                                         geometry,
                                         {2, instances},
                                         {3, mTableBuffer},
                                         {4, mWork->units},
                                         {5, mWork->hardwareList},
                                         {6, target.visibility}},
                                        "visibility hardware");
    std::vector<gpu::BindingResource> bins = binResources();
    mBinGroup = gpu::makeBindGroup(device, p.binLayout, bins, "visibility bins");
    std::vector<gpu::BindingResource> shading = shadeResources();
    shading.emplace_back(8, target.shadedLayers);
    mShadeGroup = gpu::makeBindGroup(device, p.shadeLayout, shading, "visibility shading");
    mCompositeGroup = gpu::makeBindGroup(device, p.compositeLayout,
                                         {{0, target.visibility}, {1, target.shadedLayers}},
                                         "visibility composite");
    // Over the composed frame's view, made again with it (composeFrame, ensureComposedShading).
    mComposeGroup = nullptr;
    mBinComposedGroup = nullptr;
    mShadeComposedGroup = nullptr;
}

void VisibilityStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    const bool after = drawsAfter();
    if (mTables.itemCount > 0 && mCompositeGroup) {
        // Nothing depth-tests against the composite's depth unless something is drawn after it.
        encoder.setPipeline(frame.resolvedPass ? mPipelines->compositeResolved
                            : after            ? mPipelines->composite
                                               : mPipelines->compositePixels);
        encoder.setBindGroup(0, mCompositeGroup);
        encoder.draw(3, 1, 0, 0, scene::Topology::TriangleList);
    }
    if (after) {
        mDraws.setSharedBindGroups(encoder);
        mDraws.encodeOpaque(encoder);
        mDraws.encodeBlended(encoder, mDraws.blendOrder(frame.camera.position));
    }
}

}  // namespace encore::render
