#include "render/strategies/VisibilityStrategy.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <set>
#include <string>

#include "encore/gpu/DeviceLimits.h"
#include "encore/render/VisibilityFeatures.h"
#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"
#include "render/Frustum.h"
#include "render/LodSelection.h"

namespace encore::render {

namespace {

// visibility_params.wgsl's VisibilityParams, one per view at a 256-byte stride.
struct ViewParams {
    std::uint32_t itemCount = 0;
    std::uint32_t targetWidth = 0;
    std::uint32_t viewportX = 0;
    std::uint32_t viewportY = 0;
    std::uint32_t viewportWidth = 0;
    std::uint32_t viewportHeight = 0;
    float maxComputePixels = 0.0f;
    std::uint32_t frustumTest = 0;
    std::uint32_t hardwareCapacity = 0;
    std::uint32_t binCount = 0;
    float maxWorkgroupPixels = 0.0f;
    std::uint32_t samples = 1;
};
static_assert(sizeof(ViewParams) == 48);

// visibility_cull.wgsl's Culling, one per frame (a multi-view frame's views differ only in
// their viewports: no frustum test, no occlusion, the levels of detail of GPU culling's one cull).
struct CullUniform {
    std::array<glm::vec4, 6> planes{};
    glm::mat4 viewProjection{1.0f};
    std::uint32_t lodViewCount = 0;
    float lodPixelsPerUnit = 0.0f;
    float lodThresholdPixels = 0.0f;
    std::uint32_t orthographic = 0;
    std::uint32_t occlusion = 0;
    std::uint32_t frustumTest = 0;
    float lodDistanceSlack = 0.0f;
    std::uint32_t padding = 0;
    std::array<glm::vec4, LodSelection::kMaxViews> lodViews{};
};
static_assert(offsetof(CullUniform, lodViewCount) == 160);
static_assert(offsetof(CullUniform, lodViews) == 192);
static_assert(sizeof(CullUniform) == 448);

constexpr std::uint64_t kParamsStride = 256;
constexpr std::uint64_t kBinStride = 256;  // visibility_bin_record.wgsl's record.
static_assert(kBinStride == VisibilityStrategy::kBinRecordBytes);
constexpr std::uint64_t kCounterBytes = 64;
// Byte offsets in visibility_raster.wgsl's Counters.
constexpr std::uint64_t kHardwareArguments = 16;
constexpr std::uint64_t kComputeTriangles = 32;
constexpr std::uint64_t kHardwareTriangles = 40;
// The hardware list holds at most this many triangles (16 MiB); past it they are counted as an
// overflow (visibility_raster.wgsl) rather than written.
constexpr std::uint64_t kMaxHardwareTriangles = 4u << 20;
constexpr std::uint32_t kMaxGroups = 65535;

constexpr auto kCompute = wgpu::ShaderStage::Compute;

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

wgpu::ComputePipeline computePipeline(const wgpu::Device& device,
                                      const wgpu::ShaderModule& module,
                                      const char* entryPoint,
                                      std::initializer_list<wgpu::BindGroupLayout> groups) {
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.label = entryPoint;
    descriptor.layout = gpu::makePipelineLayout(device, groups);
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = entryPoint;
    return device.CreateComputePipeline(&descriptor);
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
    mTables = buildVisibilityTables(scene, mGeometryBytes);
    ENCORE_TRY(mDraws.prepare(setup, scene, [this](scene::MeshId mesh, std::size_t primitive) {
        return !mTables.computePath[mesh.index()][primitive];
    }));

    mTableBuffer = gpu::createStorageBuffer(device, mTables.words, "visibility tables");
    mCullUniform =
        gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                          sizeof(CullUniform), "visibility culling");
    // Zero: nothing was visible before the first frame, whose second phase tests everything.
    mItemVisibility = gpu::createBuffer(device, wgpu::BufferUsage::Storage,
                                        std::max<std::uint64_t>(mTables.itemCount, 1) * 4,
                                        "visibility of items last frame");
    mPyramid = DepthPyramid();
    mUnits =
        gpu::createBuffer(device, wgpu::BufferUsage::Storage,
                          std::max<std::uint64_t>(mTables.unitCount, 1) * 8, "visibility units");
    mHardwareCapacity =
        std::uint32_t(std::clamp<std::uint64_t>(mTables.triangleCount, 1, kMaxHardwareTriangles));
    mHardwareList =
        gpu::createBuffer(device, wgpu::BufferUsage::Storage, std::uint64_t(mHardwareCapacity) * 4,
                          "visibility hardware triangles");
    mWorkgroupList =
        gpu::createBuffer(device, wgpu::BufferUsage::Storage, std::uint64_t(mHardwareCapacity) * 4,
                          "visibility workgroup triangles");
    mCounters = gpu::createBuffer(device,
                                  wgpu::BufferUsage::Storage | wgpu::BufferUsage::Indirect |
                                      wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                                  kCounterBytes, "visibility counters");
    // Unit count 0, hardware draw (0 vertices, 1 instance, 0, 0).
    std::array<std::uint32_t, kCounterBytes / 4> initial{};
    initial[5] = 1;
    mInitialCounters = gpu::createBufferFrom<std::uint32_t>(device, wgpu::BufferUsage::CopySrc,
                                                            initial, "visibility initial counters");
    const std::uint32_t persistent = persistentWorkgroups(device);
    mRasterGroups = stridingGrid(mTables.unitCount, 1, persistent);
    mWorkgroupGroups = stridingGrid(mHardwareCapacity, 1, persistent);
    mBins = gpu::createBuffer(
        device,
        wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
        std::uint64_t(mTables.binCount) * kBinStride, "visibility bins");
    ENCORE_TRY(createPipelines());
    mWidth = 0;
    mHeight = 0;
    mViewCapacity = 0;
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

Result<void> VisibilityStrategy::createPipelines() {
    using gpu::LayoutEntry;
    const wgpu::Device& device = mSetup->device;
    const auto vertex = wgpu::ShaderStage::Vertex;
    const auto fragment = wgpu::ShaderStage::Fragment;
    const auto params = LayoutEntry::uniform(0, kCompute, sizeof(ViewParams)).withDynamicOffset();
    // The frame uniform alone (frame.wgsl's group 0) for the raster passes: the frame layout's
    // lights would take one of the eight storage buffers a stage may bind.
    mFrameOnlyLayout = gpu::makeBindGroupLayout(
        device, {LayoutEntry::uniform(0, kCompute | vertex | fragment, sizeof(FrameUniform))},
        "visibility frame");
    mCullLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(2, kCompute),
         LayoutEntry::readOnlyStorage(3, kCompute), LayoutEntry::storage(4, kCompute),
         LayoutEntry::storage(5, kCompute), LayoutEntry::uniform(10, kCompute, sizeof(CullUniform)),
         LayoutEntry::storage(11, kCompute),
         LayoutEntry::texture(12, kCompute, wgpu::TextureSampleType::UnfilterableFloat)},
        "visibility culling");
    mRasterLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(1, kCompute),
         LayoutEntry::readOnlyStorage(2, kCompute), LayoutEntry::readOnlyStorage(3, kCompute),
         LayoutEntry::storage(4, kCompute), LayoutEntry::storage(5, kCompute),
         LayoutEntry::storage(6, kCompute), LayoutEntry::storage(7, kCompute),
         LayoutEntry::storage(9, kCompute)},
        "visibility raster");
    mHardwareLayout = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, vertex | fragment, sizeof(ViewParams)).withDynamicOffset(),
         LayoutEntry::readOnlyStorage(1, vertex), LayoutEntry::readOnlyStorage(2, vertex),
         LayoutEntry::readOnlyStorage(3, vertex), LayoutEntry::readOnlyStorage(4, vertex),
         LayoutEntry::readOnlyStorage(5, vertex), LayoutEntry::storage(6, fragment)},
        "visibility hardware");
    mBinLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(1, kCompute),
         LayoutEntry::readOnlyStorage(2, kCompute), LayoutEntry::readOnlyStorage(3, kCompute),
         LayoutEntry::storage(4, kCompute), LayoutEntry::storage(5, kCompute)},
        "visibility bins");
    mShadeLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(1, kCompute),
         LayoutEntry::readOnlyStorage(2, kCompute), LayoutEntry::readOnlyStorage(3, kCompute),
         LayoutEntry::readOnlyStorage(4, kCompute), LayoutEntry::readOnlyStorage(5, kCompute),
         LayoutEntry::readOnlyStorage(6, kCompute),
         LayoutEntry::readOnlyStorage(7, kCompute, kBinStride).withDynamicOffset(),
         LayoutEntry::storageTexture(8, kCompute, wgpu::TextureFormat::RGBA16Float,
                                     wgpu::StorageTextureAccess::WriteOnly,
                                     wgpu::TextureViewDimension::e2DArray)},
        "visibility shading");
    mCompositeLayout = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::readOnlyStorage(0, fragment),
         LayoutEntry::texture(1, fragment, wgpu::TextureSampleType::UnfilterableFloat,
                              wgpu::TextureViewDimension::e2DArray)},
        "visibility composite");

    shaders::ShaderLibrary& library = *mSetup->shaders;
    const wgpu::BindGroupLayout frame = mSetup->layouts->frame;
    ENCORE_TRY_ASSIGN(auto cull, library.module("visibility_cull.wgsl"));
    mCullFirst = computePipeline(device, cull, "cullFirstPhase", {mFrameOnlyLayout, mCullLayout});
    mBeginSecondPhase =
        computePipeline(device, cull, "beginSecondPhase", {mFrameOnlyLayout, mCullLayout});
    mCullSecond = computePipeline(device, cull, "cullSecondPhase", {mFrameOnlyLayout, mCullLayout});
    ENCORE_TRY_ASSIGN(auto raster, library.module("visibility_raster.wgsl"));
    mRaster = computePipeline(device, raster, "rasterMain", {mFrameOnlyLayout, mRasterLayout});
    mWorkgroupRaster =
        computePipeline(device, raster, "workgroupMain", {mFrameOnlyLayout, mRasterLayout});
    mFrameOnlyGroup = gpu::makeBindGroup(device, mFrameOnlyLayout,
                                         {{0, mSetup->frame->buffer(), 0, sizeof(FrameUniform)}},
                                         "visibility frame");

    ENCORE_TRY_ASSIGN(auto bins, library.module("visibility_bins.wgsl"));
    mBinCount = computePipeline(device, bins, "countMain", {mBinLayout});
    mBinOffsets = computePipeline(device, bins, "offsetsMain", {mBinLayout});
    mBinScatter = computePipeline(device, bins, "scatterMain", {mBinLayout});

    for (bool textured : {false, true}) {
        for (bool tangent : {false, true}) {
            // One shading pipeline serves every material of its bin kind: all features in.
            std::set<std::string, std::less<>> flags = {"SAMPLE_GRADIENT", "MATERIAL_EXTENSIONS"};
            if (textured) {
                flags.insert("MATERIAL_TEXTURES");
                flags.insert("SAMPLER_PALETTE");
            }
            if (tangent) {
                flags.insert("HAS_TANGENT");
            }
            ENCORE_TRY_ASSIGN(auto shade, library.module("visibility_shade.wgsl", flags));
            mShade[textured][tangent] = computePipeline(
                device, shade, "shadeMain",
                {frame, mShadeLayout,
                 textured ? mSetup->layouts->material : mSetup->layouts->materialUniformOnly});
        }
    }

    ENCORE_TRY_ASSIGN(auto hardware, library.module("visibility_hardware.wgsl"));
    wgpu::DepthStencilState depth{};
    depth.format = wgpu::TextureFormat::Depth32Float;
    depth.depthWriteEnabled = wgpu::OptionalBool::True;
    depth.depthCompare = wgpu::CompareFunction::Less;
    wgpu::FragmentState hardwareFragment{};
    hardwareFragment.module = hardware;
    hardwareFragment.entryPoint = "fragmentMain";
    wgpu::RenderPipelineDescriptor pipeline{};
    pipeline.label = "visibility hardware";
    pipeline.layout = gpu::makePipelineLayout(device, {mFrameOnlyLayout, mHardwareLayout});
    pipeline.vertex.module = hardware;
    pipeline.vertex.entryPoint = "vertexMain";
    pipeline.primitive.topology = wgpu::PrimitiveTopology::TriangleList;
    pipeline.primitive.cullMode = wgpu::CullMode::None;  // Back faces were culled in compute.
    pipeline.depthStencil = &depth;
    pipeline.multisample.count = mSetup->sampleCount;
    pipeline.fragment = &hardwareFragment;
    mHardware = device.CreateRenderPipeline(&pipeline);

    std::set<std::string, std::less<>> compositeFlags;
    if (mSetup->sampleCount > 1) {
        compositeFlags.insert("MULTISAMPLED");
    }
    ENCORE_TRY_ASSIGN(auto composite, library.module("visibility_composite.wgsl", compositeFlags));
    gpu::FullscreenPipelineDescriptor compositeDescriptor;
    compositeDescriptor.label = "visibility composite";
    compositeDescriptor.module = composite;
    compositeDescriptor.layout = gpu::makePipelineLayout(device, {mCompositeLayout});
    compositeDescriptor.colorFormat = mSetup->colorFormat;
    compositeDescriptor.depthFormat = mSetup->depthFormat;
    compositeDescriptor.writesDepth = true;
    compositeDescriptor.sampleCount = mSetup->sampleCount;
    mComposite = gpu::makeFullscreenPipeline(device, compositeDescriptor);
    return {};
}

void VisibilityStrategy::ensureTarget(std::uint32_t width,
                                      std::uint32_t height,
                                      std::size_t views) {
    const wgpu::Device& device = mSetup->device;
    if (views > mViewCapacity) {
        mViewCapacity = views;
        mParams = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                    views * kParamsStride, "visibility view parameters");
        mTriangleCounts =
            gpu::createBuffer(device, wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
                              views * 8, "visibility triangle counts");
        mWidth = 0;  // The bind groups hold the parameters.
    }
    if (width == mWidth && height == mHeight) {
        return;
    }
    mWidth = width;
    mHeight = height;
    // An entry per sample: 8 bytes in the visibility buffer, 4 in the binned list, a texel of
    // the shaded colour (2x2 per pixel at four samples, visibility_samples.wgsl).
    const std::uint32_t samples = mSetup->sampleCount;
    const std::uint64_t entries = std::uint64_t(width) * height * samples;
    mShadeGroups = stridingGrid(entries, 64, persistentWorkgroups(device));
    mVisibility = gpu::createBuffer(device, wgpu::BufferUsage::Storage | wgpu::BufferUsage::CopyDst,
                                    entries * 8, "visibility buffer");
    mPixels = gpu::createBuffer(device, wgpu::BufferUsage::Storage, entries * 4,
                                "visibility binned pixels");
    wgpu::TextureDescriptor texture{};
    texture.size = {width, height, samples};  // A layer per sample.
    texture.format = wgpu::TextureFormat::RGBA16Float;
    texture.usage = wgpu::TextureUsage::StorageBinding | wgpu::TextureUsage::TextureBinding;
    texture.label = "visibility shaded colour";
    mShaded = device.CreateTexture(&texture);
    texture.size = {width, height, 1};
    texture.format = wgpu::TextureFormat::Depth32Float;
    texture.usage = wgpu::TextureUsage::RenderAttachment;
    texture.sampleCount = samples;
    texture.label = "visibility hardware depth";
    mHardwareDepth = device.CreateTexture(&texture);

    auto pyramid =
        DepthPyramid::createFromVisibility(device, *mSetup->shaders, mVisibility, width, height);
    // The shader is embedded: a failure here is a bug, not an input error.
    ENCORE_CHECK(pyramid.ok(), "the depth pyramid cannot be built: " + pyramid.error().message);
    mPyramid = std::move(*pyramid);

    const wgpu::Buffer& instances = mScene->instances().buffer();
    const gpu::BindingResource params(0, mParams, 0, sizeof(ViewParams));
    mCullGroup = gpu::makeBindGroup(device, mCullLayout,
                                    {params,
                                     {2, instances},
                                     {3, mTableBuffer},
                                     {4, mUnits},
                                     {5, mCounters},
                                     {10, mCullUniform},
                                     {11, mItemVisibility},
                                     {12, mPyramid.view()}},
                                    "visibility culling");
    const gpu::BindingResource geometry(1, mGeometry, 0, mGeometryBytes);
    mRasterGroup = gpu::makeBindGroup(device, mRasterLayout,
                                      {params,
                                       geometry,
                                       {2, instances},
                                       {3, mTableBuffer},
                                       {4, mUnits},
                                       {5, mCounters},
                                       {6, mHardwareList},
                                       {7, mVisibility},
                                       {9, mWorkgroupList}},
                                      "visibility raster");
    mHardwareGroup = gpu::makeBindGroup(device, mHardwareLayout,
                                        {params,
                                         geometry,
                                         {2, instances},
                                         {3, mTableBuffer},
                                         {4, mUnits},
                                         {5, mHardwareList},
                                         {6, mVisibility}},
                                        "visibility hardware");
    mBinGroup = gpu::makeBindGroup(
        device, mBinLayout,
        {params, {1, mTableBuffer}, {2, mUnits}, {3, mVisibility}, {4, mBins}, {5, mPixels}},
        "visibility bins");
    wgpu::TextureViewDescriptor layers{};
    layers.dimension = wgpu::TextureViewDimension::e2DArray;  // Even with one layer.
    const wgpu::TextureView shadedLayers = mShaded.CreateView(&layers);
    mShadeGroup = gpu::makeBindGroup(device, mShadeLayout,
                                     {params,
                                      geometry,
                                      {2, instances},
                                      {3, mTableBuffer},
                                      {4, mUnits},
                                      {5, mVisibility},
                                      {6, mPixels},
                                      {7, mBins, 0, kBinStride},
                                      {8, shadedLayers}},
                                     "visibility shading");
    mCompositeGroup = gpu::makeBindGroup(
        device, mCompositeLayout, {{0, mVisibility}, {1, shadedLayers}}, "visibility composite");
}

void VisibilityStrategy::beforePass(const wgpu::CommandEncoder& commands, const FrameState& frame) {
    const std::size_t views = std::max<std::size_t>(frame.views.size(), 1);
    ensureTarget(frame.targetWidth, frame.targetHeight, views);
    mLastViewCount = 0;
    mOcclusion = false;
    if (mTables.itemCount == 0 || frame.targetWidth == 0 || frame.targetHeight == 0) {
        return;
    }
    // As GPU culling: two phases in frames of one view, and not while a frozen culling camera
    // sees another view than the one drawn.
    mOcclusion = views == 1 && frame.culling.occlusion && !frame.cullingCamera;
    const std::uint32_t viewWidth = frame.targetWidth / std::uint32_t(views);
    std::vector<std::uint8_t> params(views * kParamsStride, 0);
    for (std::size_t view = 0; view < views; ++view) {
        ViewParams p;
        p.itemCount = mTables.itemCount;
        p.targetWidth = frame.targetWidth;
        p.viewportX = std::uint32_t(view) * viewWidth;
        p.viewportWidth = viewWidth;
        p.viewportHeight = frame.targetHeight;
        p.maxComputePixels = std::clamp(frame.culling.computeRasterPixels, 0.0f, kMaxComputePixels);
        p.maxWorkgroupPixels =
            std::clamp(frame.culling.workgroupRasterPixels, 0.0f, kMaxWorkgroupPixels);
        p.frustumTest = views == 1 ? 1 : 0;
        p.hardwareCapacity = mHardwareCapacity;
        p.binCount = mTables.binCount;
        p.samples = mSetup->sampleCount;
        std::memcpy(params.data() + view * kParamsStride, &p, sizeof(p));
    }
    mSetup->queue.WriteBuffer(mParams, 0, params.data(), params.size());
    writeCullUniform(frame, views);
    commands.ClearBuffer(mVisibility);
    for (std::size_t view = 0; view < views; ++view) {
        if (views > 1) {
            mSetup->frame->selectView(commands, view);
        }
        encodeView(commands, frame, view, std::uint32_t(view) * viewWidth, viewWidth);
    }
    mLastViewCount = views;
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
    mSetup->queue.WriteBuffer(mCullUniform, 0, &uniform, sizeof(uniform));
}

void VisibilityStrategy::encodeRaster(const wgpu::ComputePassEncoder& pass,
                                      std::uint32_t paramsOffset) const {
    pass.SetBindGroup(1, mRasterGroup, 1, &paramsOffset);
    pass.SetPipeline(mRaster);
    pass.DispatchWorkgroups(mRasterGroups);
    pass.SetPipeline(mWorkgroupRaster);
    pass.DispatchWorkgroups(mWorkgroupGroups);
}

void VisibilityStrategy::encodeHardwareRaster(const wgpu::CommandEncoder& commands,
                                              const FrameState& frame,
                                              std::uint32_t paramsOffset,
                                              std::uint32_t viewX,
                                              std::uint32_t viewWidth,
                                              const char* timerLabel) const {
    wgpu::RenderPassDepthStencilAttachment depth{};
    depth.view = mHardwareDepth.CreateView();
    depth.depthLoadOp = wgpu::LoadOp::Clear;
    depth.depthStoreOp = wgpu::StoreOp::Discard;
    depth.depthClearValue = 1.0f;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "visibility: hardware raster";
    descriptor.depthStencilAttachment = &depth;
    descriptor.timestampWrites = frame.timer ? frame.timer->nextPass(timerLabel) : nullptr;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    pass.SetViewport(float(viewX), 0.0f, float(viewWidth), float(mHeight), 0.0f, 1.0f);
    pass.SetPipeline(mHardware);
    pass.SetBindGroup(0, mFrameOnlyGroup);
    pass.SetBindGroup(1, mHardwareGroup, 1, &paramsOffset);
    pass.DrawIndirect(mCounters, kHardwareArguments);
    pass.End();
}

void VisibilityStrategy::encodeView(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame,
                                    std::size_t view,
                                    std::uint32_t viewX,
                                    std::uint32_t viewWidth) {
    const std::uint32_t paramsOffset = std::uint32_t(view * kParamsStride);
    const wgpu::BindGroup& frameGroup = mSetup->frame->bindGroup();
    const std::uint32_t itemGroups = groupsFor(mTables.itemCount, 64);
    auto dispatchItems = [&](const wgpu::ComputePassEncoder& pass,
                             const wgpu::ComputePipeline& cull) {
        pass.SetPipeline(cull);
        pass.DispatchWorkgroups(std::min(itemGroups, kMaxGroups),
                                groupsFor(itemGroups, kMaxGroups));
    };
    auto bindCull = [&](const wgpu::ComputePassEncoder& pass) {
        pass.SetBindGroup(0, mFrameOnlyGroup);
        pass.SetBindGroup(1, mCullGroup, 1, &paramsOffset);
    };
    commands.CopyBufferToBuffer(mInitialCounters, 0, mCounters, 0, kCounterBytes);
    commands.ClearBuffer(mBins);
    {
        // Everything in the frustum, or (two phases) what of it was visible last frame.
        wgpu::ComputePassDescriptor descriptor{};
        descriptor.label = "visibility: culling and compute raster";
        descriptor.timestampWrites =
            frame.timer ? frame.timer->nextPass("visibility culling and raster") : nullptr;
        wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
        bindCull(pass);
        dispatchItems(pass, mCullFirst);
        encodeRaster(pass, paramsOffset);
        pass.End();
    }
    encodeHardwareRaster(commands, frame, paramsOffset, viewX, viewWidth,
                         "visibility hardware raster");
    if (mOcclusion) {
        // The rest of the frustum against the pyramid of what phase 1 drew (both rasters).
        wgpu::ComputePassDescriptor descriptor{};
        descriptor.label = "visibility: depth pyramid, second culling and raster";
        descriptor.timestampWrites =
            frame.timer ? frame.timer->nextPass("visibility occlusion culling and raster")
                        : nullptr;
        wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
        mPyramid.encode(pass);
        bindCull(pass);  // The pyramid's dispatches bound their own group 0.
        pass.SetPipeline(mBeginSecondPhase);
        pass.DispatchWorkgroups(1);
        dispatchItems(pass, mCullSecond);
        encodeRaster(pass, paramsOffset);
        pass.End();
        encodeHardwareRaster(commands, frame, paramsOffset, viewX, viewWidth,
                             "visibility hardware raster (second phase)");
    }
    {
        wgpu::ComputePassDescriptor descriptor{};
        descriptor.label = "visibility: binning and shading";
        descriptor.timestampWrites =
            frame.timer ? frame.timer->nextPass("visibility shading") : nullptr;
        wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
        pass.SetBindGroup(0, mBinGroup, 1, &paramsOffset);
        const std::uint32_t columns = groupsFor(viewWidth, 8);
        const std::uint32_t rows = groupsFor(mHeight, 8);
        pass.SetPipeline(mBinCount);
        pass.DispatchWorkgroups(columns, rows);
        pass.SetPipeline(mBinOffsets);
        pass.DispatchWorkgroups(1);
        pass.SetPipeline(mBinScatter);
        pass.DispatchWorkgroups(columns, rows);
        pass.SetBindGroup(0, frameGroup);
        const MaterialResources& materials = mScene->materials();
        for (std::uint32_t bin : mTables.bins) {
            const scene::MaterialId material(bin / 2);
            const bool textured = materials.textured(material);
            pass.SetPipeline(mShade[textured][bin & 1]);
            const std::uint32_t offsets[] = {paramsOffset, std::uint32_t(bin * kBinStride)};
            pass.SetBindGroup(1, mShadeGroup, 2, offsets);
            pass.SetBindGroup(2, materials.bindGroup(material));
            pass.DispatchWorkgroups(mShadeGroups);
        }
        pass.End();
    }
    commands.CopyBufferToBuffer(mCounters, kComputeTriangles, mTriangleCounts, view * 8, 4);
    commands.CopyBufferToBuffer(mCounters, kHardwareTriangles, mTriangleCounts, view * 8 + 4, 4);
}

std::optional<GpuTriangleCounts> VisibilityStrategy::gpuTriangleCounts() const {
    if (!mTriangleCounts) {
        return std::nullopt;
    }
    return GpuTriangleCounts{mTriangleCounts, 4, 0, mTables.triangleCount};
}

void VisibilityStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    if (mTables.itemCount > 0 && mCompositeGroup) {
        encoder.setPipeline(mComposite);
        encoder.setBindGroup(0, mCompositeGroup);
        encoder.draw(3, 1, 0, 0, scene::Topology::TriangleList);
    }
    if (!mDraws.opaque().empty() || !mDraws.blended().empty()) {
        mDraws.setSharedBindGroups(encoder);
        mDraws.encodeOpaque(encoder);
        mDraws.encodeBlended(encoder, mDraws.blendOrder(frame.camera.position));
    }
}

}  // namespace encore::render
