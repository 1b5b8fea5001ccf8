#include "render/visibility/VisibilityStrategy.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "encore/gpu/DeviceLimits.h"
#include "gpu/BindingResource.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/culling/Frustum.h"
#include "render/culling/LodSelection.h"
#include "render/visibility/KeptStrategyObjects.h"
#include "render/visibility/VisibilityFeatures.h"
#include "render/visibility/VisibilityPhasePasses.h"

namespace encore::render {

namespace {

using ViewParams = VisibilityViewParams;
using CullUniform = VisibilityCullUniform;

constexpr std::uint64_t kParamsStride = VisibilityTarget::kParamsStride;
constexpr std::uint64_t kCounterBytes = VisibilityPipelines::kCounterBytes;
// Byte offsets in visibility_raster.wgsl's Counters.
constexpr std::uint64_t kHardwareArguments = 16;
constexpr std::uint64_t kComputeTriangles = 32;  // Then the hardware triangles' count.
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
constexpr std::uint32_t kMaxGroups = 65535;

std::uint32_t groupsFor(std::uint64_t threads, std::uint32_t size) {
    return std::uint32_t((threads + size - 1) / size);
}

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
        std::uint32_t(std::min<std::uint64_t>(groupsFor(work, perGroup), limit)), 1, limit);
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
                               sizeof(CullUniform), "visibility culling");
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

void VisibilityStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    const std::size_t views = std::max<std::size_t>(frame.views.size(), 1);
    ensureTarget(frame.targetWidth, frame.targetHeight, views);
    // At one sample a frame composed in compute is shaded into place, its uncovered pixels
    // written by the binning (or the shading of a scene of one bin): no composition pass (on the
    // H100 0.018 ms of a 1280x720 frame).
    mComposedShading = frame.composedBackground.has_value() && mSetup->sampleCount == 1;
    if (mComposedShading) {
        ensureComposedShading(frame.composedView, *frame.composedBackground);
    }
    mLastViewCount = 0;
    mOcclusion = false;
    if (mTables.itemCount == 0 || frame.targetWidth == 0 || frame.targetHeight == 0) {
        return;
    }
    copyMaterialTable(commands);
    if (shadesEveryTile()) {
        writeEveryTileRecord();
    }
    // As GPU culling: two phases in frames of one view, and not while a frozen culling camera
    // sees another view than the one drawn.
    mOcclusion = views == 1 && frame.culling.occlusion && !frame.cullingCamera;
    // Frames of one view test items against the frustum by their world spheres while the
    // transforms hold still: computed in the first static frame, kept until one moves (a frame
    // that moves transforms tests with the matrices, so animation pays nothing for them).
    const bool moved = mTransformsMoved || frame.transformsAnimated;
    mTransformsMoved = false;
    mSpheresCurrent = mSpheresCurrent && !moved;
    mComputeSpheres = views == 1 && !moved && !mSpheresCurrent;
    mSpheresCurrent = mSpheresCurrent || mComputeSpheres;
    const std::uint32_t viewWidth = frame.targetWidth / std::uint32_t(views);
    if (!computeTakesAll(frame.culling)) {
        mTarget->ensureHardwareDepth(*mSetup, viewWidth);  // The hardware raster's attachment.
    }
    // A slot per view, then one per round of bins of each group of views that bins and shading
    // take at once.
    const std::size_t groups = VisibilityTarget::groupsFor(views);
    const std::uint32_t rounds = VisibilityTarget::roundsFor(mTables.binCount);
    std::vector<std::uint8_t> params(
        VisibilityTarget::slotsFor(views, mTables.binCount) * kParamsStride, 0);
    ViewParams p;
    p.itemCount = mTables.itemCount;
    p.targetWidth = frame.targetWidth;
    p.viewportHeight = frame.targetHeight;
    p.maxComputePixels = std::clamp(frame.culling.computeRasterPixels, 0.0f, kMaxComputePixels);
    p.maxWorkgroupPixels =
        std::clamp(frame.culling.workgroupRasterPixels, 0.0f, kMaxWorkgroupPixels);
    p.computeTakesAll = computeTakesAll(frame.culling) ? 1 : 0;
    p.frustumTest = views == 1 ? 1 : 0;
    p.hardwareCapacity = mHardwareCapacity;
    p.samples = mSetup->sampleCount;
    p.workgroupBlocks = mWorkgroupBlocks;
    p.workgroupRecords = mWorkgroupRecords;
    for (std::size_t view = 0; view < views; ++view) {
        p.viewportX = std::uint32_t(view) * viewWidth;
        p.viewportWidth = viewWidth;
        std::memcpy(params.data() + view * kParamsStride, &p, sizeof(p));
        // The view's frame uniform (what the renderer writes for it), for the shading of the
        // whole group: written with the slots rather than copied on the GPU view by view.
        const FrameUniform uniform = frameUniformOf(
            frame.views.empty() ? frame.camera : frame.views[view], frame.timeSeconds, view, views);
        std::memcpy(params.data() + view * kParamsStride + VisibilityTarget::kSlotFrameOffset,
                    &uniform, sizeof(uniform));
    }
    for (std::size_t group = 0; group < groups; ++group) {
        const std::size_t first = group * VisibilityTarget::kSlotViews;
        p.viewportX = std::uint32_t(first) * viewWidth;
        p.viewportWidth =
            std::uint32_t(std::min(views - first, VisibilityTarget::kSlotViews)) * viewWidth;
        for (std::uint32_t round = 0; round < rounds; ++round) {
            p.firstBin = round * VisibilityTarget::kRoundBins;
            std::memcpy(params.data() + (views + group * rounds + round) * kParamsStride, &p,
                        sizeof(p));
        }
    }
    mSetup->queue.WriteBuffer(mTarget->params, 0, params.data(), params.size());
    writeCullUniform(frame, views);
    // A multi-view frame's cull is the same for every view (no frustum test, no occlusion, the
    // levels of one cull for all views): it runs once, and each view's raster starts from the
    // counters it left.
    const bool culledOnce = views > 1;
    if (culledOnce) {
        encodeCull(commands, frame);
    }
    for (std::size_t group = 0; group < groups; ++group) {
        const std::size_t first = group * VisibilityTarget::kSlotViews;
        const std::size_t last = std::min(views, first + VisibilityTarget::kSlotViews);
        for (std::size_t view = first; view < last; ++view) {
            if (views > 1) {
                mSetup->frame->selectView(commands, view);  // The raster's group 0.
            }
            encodeView(commands, frame, view, viewWidth, culledOnce);
        }
        encodeShading(commands, frame, views, first, views + group * rounds,
                      std::uint32_t(last - first) * viewWidth);
    }
    mLastViewCount = views;
}

void VisibilityStrategy::encodeCull(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame) const {
    commands.CopyBufferToBuffer(mPipelines->initialCounters, 0, mCounters, 0, kCounterBytes);
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "visibility: culling";
    descriptor.timestampWrites =
        frame.timer ? frame.timer->nextPass("visibility culling") : nullptr;
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    dispatchClear(pass);
    const std::uint32_t paramsOffset = 0;
    pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
    pass.SetBindGroup(1, mCullGroup, 1, &paramsOffset);
    dispatchItems(pass, mPipelines->cullFirst);
    pass.End();
    commands.CopyBufferToBuffer(mCounters, 0, mCulledCounters, 0, kCounterBytes);
}

void VisibilityStrategy::dispatchClear(const wgpu::ComputePassEncoder& pass) const {
    const std::uint64_t entries = mTarget->visibility.GetSize() / 8;
    pass.SetPipeline(mPipelines->clear);
    pass.SetBindGroup(0, mClearGroup);
    pass.DispatchWorkgroups(
        std::uint32_t(std::min<std::uint64_t>((entries + 255) / 256, kMaxGroups)));
}

void VisibilityStrategy::dispatchItems(const wgpu::ComputePassEncoder& pass,
                                       const wgpu::ComputePipeline& cull) const {
    const std::uint32_t itemGroups = groupsFor(mTables.itemCount, 64);
    pass.SetPipeline(cull);
    pass.DispatchWorkgroups(std::min(itemGroups, kMaxGroups), groupsFor(itemGroups, kMaxGroups));
}

void VisibilityStrategy::writeCullUniform(const FrameState& frame, std::size_t views) const {
    // What GpuCuller's first phase writes for the same frame: the culling camera's frustum and
    // the levels of detail of one cull serving every view.
    const Camera& camera = frame.cullingCamera.value_or(frame.camera);
    CullUniform uniform;
    uniform.viewProjection = camera.projection * camera.view;
    if (views == 1) {
        const Frustum frustum = Frustum::fromViewProjection(uniform.viewProjection);
        std::copy(frustum.planes.begin(), frustum.planes.end(), uniform.planes.begin());
        uniform.frustumTest = 1;
    }
    const LodSelection lod =
        lodSelection(camera, frame.cullingCamera ? std::span<const Camera>() : frame.views,
                     frame.targetHeight, frame.culling);
    uniform.lodViews = lod.views;
    uniform.lodViewCount = lod.viewCount;
    uniform.lodPixelsPerUnit = lod.pixelsPerUnit;
    uniform.lodThresholdPixels = lod.thresholdPixels;
    uniform.orthographic = lod.orthographic;
    uniform.lodDistanceSlack = lod.distanceSlack;
    uniform.occlusion = mOcclusion ? 1 : 0;
    uniform.clusterCulling = frame.culling.clusterCulling ? 1 : 0;
    uniform.worldSpheres = views == 1 && mSpheresCurrent ? 1 : 0;
    uniform.unitListBase = mTables.unitListBase();
    mSetup->queue.WriteBuffer(mCullUniform, 0, &uniform, sizeof(uniform));
}

void VisibilityStrategy::encodeRaster(VisibilityPhasePasses& passes,
                                      std::uint32_t paramsOffset,
                                      bool secondPhase) const {
    auto dispatch = [&](const char* timerLabel, const wgpu::ComputePipeline& pipeline,
                        std::uint32_t groups) {
        const wgpu::ComputePassEncoder& pass = passes.step(timerLabel);
        pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
        pass.SetBindGroup(1, mRasterGroup, 1, &paramsOffset);
        pass.SetPipeline(pipeline);
        pass.DispatchWorkgroups(groups);
    };
    dispatch(secondPhase ? "visibility compute raster (second phase)" : "visibility compute raster",
             mPipelines->raster, mRasterGroups);
    dispatch(
        secondPhase ? "visibility workgroup raster (second phase)" : "visibility workgroup raster",
        mPipelines->workgroupRaster, mWorkgroupGroups);
}

void VisibilityStrategy::encodeHardwareRaster(const wgpu::CommandEncoder& commands,
                                              const FrameState& frame,
                                              std::uint32_t paramsOffset,
                                              std::uint32_t viewWidth,
                                              const char* timerLabel) const {
    if (computeTakesAll(frame.culling)) {
        return;  // The workgroup raster clipped what would have come here.
    }
    // The attachment only sets the pass's size and samples: the pipeline neither tests nor
    // writes it, so it is loaded and stored as it is (Dawn clears it once, on first use),
    // rather than cleared per view, which on the H100's graphics units took 0.06 ms per view
    // of 512x512 at four samples.
    wgpu::RenderPassDepthStencilAttachment depth{};
    depth.view = mTarget->hardwareDepthView;
    depth.depthLoadOp = wgpu::LoadOp::Load;
    depth.depthStoreOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "visibility: hardware raster";
    descriptor.depthStencilAttachment = &depth;
    descriptor.timestampWrites = frame.timer ? frame.timer->nextPass(timerLabel) : nullptr;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    // The attachment is one view's size: the view at the origin, its fragments shifted back to
    // the view's place in the strip (visibility_hardware.wgsl).
    pass.SetViewport(0.0f, 0.0f, float(viewWidth), float(mTarget->height), 0.0f, 1.0f);
    pass.SetPipeline(mPipelines->hardware);
    pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
    pass.SetBindGroup(1, mHardwareGroup, 1, &paramsOffset);
    pass.DrawIndirect(mCounters, kHardwareArguments);
    pass.End();
}

void VisibilityStrategy::encodeView(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame,
                                    std::size_t view,
                                    std::uint32_t viewWidth,
                                    bool culled) {
    const std::uint32_t paramsOffset = std::uint32_t(view * kParamsStride);
    auto bindCull = [&](const wgpu::ComputePassEncoder& pass) {
        pass.SetBindGroup(0, mPipelines->frameOnlyGroup);
        pass.SetBindGroup(1, mCullGroup, 1, &paramsOffset);
    };
    const wgpu::Buffer& counters = culled ? mCulledCounters : mPipelines->initialCounters;
    commands.CopyBufferToBuffer(counters, 0, mCounters, 0, kCounterBytes);
    {
        // Everything in the frustum, or (two phases) what of it was visible last frame.
        VisibilityPhasePasses passes(commands, frame.timer,
                                     "visibility: culling and compute raster");
        if (!culled) {
            // The frame's first pass (one view): the clear runs beside the culling.
            const wgpu::ComputePassEncoder& pass = passes.step("visibility culling");
            dispatchClear(pass);
            bindCull(pass);
            if (mComputeSpheres) {
                dispatchItems(pass, mPipelines->worldSpheres);
            }
            dispatchItems(pass, mPipelines->cullFirst);
        }
        encodeRaster(passes, paramsOffset, false);
    }
    encodeHardwareRaster(commands, frame, paramsOffset, viewWidth, "visibility hardware raster");
    if (mOcclusion) {
        {
            // The rest of the frustum against the pyramid of what phase 1 drew (both rasters).
            VisibilityPhasePasses passes(commands, frame.timer,
                                         "visibility: depth pyramid, second culling and raster");
            mTarget->pyramid.encode(passes.step("visibility depth pyramid"));
            const wgpu::ComputePassEncoder& pass = passes.step("visibility occlusion culling");
            bindCull(pass);  // The pyramid's dispatches bound their own group 0.
            pass.SetPipeline(mPipelines->beginSecondPhase);
            pass.DispatchWorkgroups(1);
            dispatchItems(pass, mPipelines->cullSecond);
            encodeRaster(passes, paramsOffset, true);
        }
        encodeHardwareRaster(commands, frame, paramsOffset, viewWidth,
                             "visibility hardware raster (second phase)");
    }
    if (culled) {  // Frames of several views keep each one's counts; one view's stay put.
        commands.CopyBufferToBuffer(mCounters, kComputeTriangles, mTarget->triangleCounts, view * 8,
                                    8);
    }
}

StrategyReport VisibilityStrategy::report() const {
    StrategyReport report;
    if (mCullGroup) {  // Before the first frame the kept counts are another scene's.
        const std::uint64_t offset = rasterCountsOffset(0);
        report.gpuTriangleCounts =
            GpuTriangleCounts{rasterCounts(), offset + 4, offset, mTables.triangleCount};
    }
    return report;
}

const wgpu::Buffer& VisibilityStrategy::rasterCounts() const {
    return mLastViewCount > 1 ? mTarget->triangleCounts : mCounters;
}

std::uint64_t VisibilityStrategy::rasterCountsOffset(std::size_t view) const {
    return mLastViewCount > 1 ? view * 8 : kComputeTriangles;
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
