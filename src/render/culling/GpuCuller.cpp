#include "render/culling/GpuCuller.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <map>
#include <numeric>

#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"
#include "render/AnimationBuffers.h"
#include "render/RenderEncoder.h"
#include "render/culling/CullingUniform.h"
#include "render/culling/LodSelection.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;            // culling.wgsl's kWorkgroupSize.
constexpr std::uint32_t kVisibleAlignmentEntries = 64;  // 256 bytes: storage offset alignment.

// The triangles one instance of a draw of `elementCount` indices (or vertices) draws.
std::uint32_t trianglesOf(const CulledDraw& draw, std::uint32_t elementCount) {
    return static_cast<std::uint32_t>(triangleCount(draw.topology, elementCount));
}

// Every culling buffer is bound whole as storage. The per-draw buffer checked is the largest of
// its kind (20 bytes of indirect arguments per draw and phase).
Result<void> checkCullingBuffers(const gpu::DeviceLimits& limits,
                                 std::size_t levelDrawCount,
                                 std::uint32_t slotCount,
                                 std::uint64_t visibleBytes) {
    const std::string draws = std::to_string(levelDrawCount) + " culled draws";
    const std::string slots = std::to_string(slotCount) + " instances";
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, std::uint64_t(levelDrawCount) * GpuCuller::kPhases * 5 * 4 + 4,
        "The indirect draw arguments of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(levelDrawCount) * 2 * 16,
                                        "The culling records of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(slotCount) * sizeof(SlotBounds),
                                        "The culling bounds of " + slots));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, visibleBytes,
        "The visible-instance lists of " + draws + " over " + slots +
            " (two lists per draw, as long as its instance count, rounded to 64 entries, and "
            "one word per instance)"));
    return {};
}

// Records: per draw (firstLevel, levelCount, 0, 0), then per level draw (visibleBase,
// argumentsOffset, triangles, error bits).
struct CullingRecords {
    std::vector<glm::uvec4> primitives;
    std::vector<glm::uvec4> levels;
    std::vector<std::uint32_t> firstLevel;   // Per draw: its first level draw.
    std::vector<std::uint32_t> visibleBase;  // Per level draw: its list's first entry.
    // Entries of one phase's lists. 64 bits until checked: thousands of primitives of a million
    // instances pass 2^32 entries.
    std::uint64_t phaseVisible = 0;
    std::uint32_t largestList = 1;  // Entries of the longest list.
};

CullingRecords cullingRecords(std::span<const CulledDraw> draws) {
    CullingRecords records;
    std::uint64_t nextBase = 0;
    for (const CulledDraw& draw : draws) {
        const auto firstLevel = static_cast<std::uint32_t>(records.levels.size());
        records.firstLevel.push_back(firstLevel);
        records.primitives.push_back({firstLevel, draw.levelCount(), 0, 0});
        const std::uint32_t capacity = std::max(draw.instances.count, 1u);
        records.largestList = std::max(records.largestList, capacity);
        for (std::uint32_t level = 0; level < draw.levelCount(); ++level) {
            const std::uint32_t elements =
                level == 0 ? draw.elementCount : draw.coarserLevels[level - 1].indexCount;
            const float error = level == 0 ? 0.0f : draw.coarserLevels[level - 1].error;
            const auto levelDraw = static_cast<std::uint32_t>(records.levels.size());
            records.visibleBase.push_back(static_cast<std::uint32_t>(nextBase));
            records.levels.push_back({static_cast<std::uint32_t>(nextBase), levelDraw * 5,
                                      trianglesOf(draw, elements),
                                      std::bit_cast<std::uint32_t>(error)});
            nextBase += (std::uint64_t(capacity) + kVisibleAlignmentEntries - 1) /
                        kVisibleAlignmentEntries * kVisibleAlignmentEntries;
        }
    }
    records.phaseVisible = nextBase;
    return records;
}

// Arguments: instanceCount starts at 0; the first cull pass fills it. drawIndexedIndirect
// reads five words (count, instances, first index, base vertex, first instance),
// drawIndirect the first four; one record layout serves both. The last word counts the
// triangles drawn (GpuCuller::drawnTrianglesOffset).
std::vector<std::uint32_t> argumentRecords(std::span<const CulledDraw> draws) {
    std::vector<std::uint32_t> arguments;
    for (std::uint32_t phase = 0; phase < GpuCuller::kPhases; ++phase) {
        for (const CulledDraw& draw : draws) {
            arguments.insert(arguments.end(), {draw.elementCount, 0, 0, 0, 0});
            for (const DrawLevel& level : draw.coarserLevels) {
                arguments.insert(arguments.end(), {level.indexCount, 0, level.firstIndex, 0, 0});
            }
        }
    }
    arguments.push_back(0);
    return arguments;
}

// Each slot lists the culled draws of its instance range, contiguous in the primitive
// records; slots whose mesh has no culled draw (all its primitives blended) list none. Returns
// the primitive records in that order and sets each slot's firstDraw and drawCount.
std::vector<glm::uvec4> primitiveRecordsBySlot(std::span<const CulledDraw> draws,
                                               std::span<const glm::uvec4> primitiveRecords,
                                               std::span<SlotBounds> slots) {
    std::map<std::uint32_t, std::vector<std::uint32_t>> drawsOfRange;  // By first slot.
    for (std::uint32_t i = 0; i < draws.size(); ++i) {
        drawsOfRange[draws[i].instances.first].push_back(i);
    }
    std::vector<glm::uvec4> records;
    for (const auto& [firstSlot, drawIndices] : drawsOfRange) {
        const auto firstDraw = static_cast<std::uint32_t>(records.size());
        for (std::uint32_t draw : drawIndices) {
            records.push_back(primitiveRecords[draw]);
        }
        const InstanceRange range = draws[drawIndices.front()].instances;
        for (std::uint32_t slot = range.first; slot < range.first + range.count; ++slot) {
            slots[slot].firstDraw = firstDraw;
            slots[slot].drawCount = static_cast<std::uint32_t>(drawIndices.size());
        }
    }
    return records;
}

struct CullingPipelines {
    wgpu::BindGroupLayout cullLayout;
    wgpu::BindGroupLayout pyramidLayout;
    wgpu::ComputePipeline reset;
    wgpu::ComputePipeline cullFirst;
    wgpu::ComputePipeline cullSecond;
};

Result<CullingPipelines> createCullingPipelines(const wgpu::Device& device,
                                                shaders::ShaderLibrary& shaders) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("culling.wgsl"));
    // Explicit layouts, shared by the entry points: layouts derived from each shader entry point
    // would be distinct and their bind groups incompatible. The second phase adds the pyramid.
    constexpr auto kCompute = wgpu::ShaderStage::Compute;
    using gpu::LayoutEntry;
    CullingPipelines pipelines;
    pipelines.cullLayout = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, kCompute), LayoutEntry::readOnlyStorage(1, kCompute),
         LayoutEntry::readOnlyStorage(2, kCompute), LayoutEntry::readOnlyStorage(3, kCompute),
         LayoutEntry::readOnlyStorage(4, kCompute), LayoutEntry::storage(5, kCompute),
         LayoutEntry::storage(6, kCompute), LayoutEntry::readOnlyStorage(7, kCompute),
         LayoutEntry::readOnlyStorage(8, kCompute)},
        "culling");
    pipelines.pyramidLayout = gpu::makeBindGroupLayout(
        device, {LayoutEntry::texture(0, kCompute, wgpu::TextureSampleType::UnfilterableFloat)},
        "culling depth pyramid");

    auto computePipeline = [&](const char* entryPoint, bool withPyramid) {
        wgpu::ComputePipelineDescriptor descriptor{};
        descriptor.label = entryPoint;
        descriptor.layout =
            withPyramid
                ? gpu::makePipelineLayout(device, {pipelines.cullLayout, pipelines.pyramidLayout})
                : gpu::makePipelineLayout(device, {pipelines.cullLayout});
        descriptor.compute.module = module;
        descriptor.compute.entryPoint = entryPoint;
        return device.CreateComputePipeline(&descriptor);
    };
    pipelines.reset = computePipeline("resetCounts", false);
    pipelines.cullFirst = computePipeline("cullFirstPhase", false);
    pipelines.cullSecond = computePipeline("cullSecondPhase", true);
    return pipelines;
}

}  // namespace

Result<GpuCuller> GpuCuller::create(const RenderSetup& setup,
                                    const InstanceBuffer& instances,
                                    const AnimationBuffers* animation,
                                    CullingBounds bounds,
                                    std::vector<CulledDraw> draws) {
    GpuCuller culler;
    culler.mSetup = &setup;
    culler.mDraws = std::move(draws);
    culler.mBounds = std::move(bounds);
    culler.mSlotCount = static_cast<std::uint32_t>(culler.mBounds.slots.size());
    if (culler.mDraws.empty() || culler.mSlotCount == 0) {
        return culler;  // Nothing to cull: encoding does nothing.
    }
    const wgpu::Device& device = setup.device;

    CullingRecords records = cullingRecords(culler.mDraws);
    culler.mFirstLevel = std::move(records.firstLevel);
    culler.mVisibleBase = std::move(records.visibleBase);
    culler.mLevelDrawCount = static_cast<std::uint32_t>(records.levels.size());
    const std::uint64_t listBytes = std::uint64_t(records.largestList) * 4;
    // Phase 2's lists follow phase 1's; the slots' visibility follows both. The draw bind group
    // binds listBytes from any list's start; the last list's binding ends within the
    // visibility words, since no list is longer than there are slots.
    const std::uint64_t phaseVisible = records.phaseVisible;
    const std::uint64_t visibilityBase = phaseVisible * kPhases;
    const std::uint64_t visibleBytes = (visibilityBase + culler.mSlotCount) * 4;
    ENCORE_TRY(
        checkCullingBuffers(setup.limits, records.levels.size(), culler.mSlotCount, visibleBytes));
    ENCORE_TRY(
        gpu::checkStorageBinding(setup.limits, culler.mBounds.shapes.size() * sizeof(glm::vec4),
                                 "The joint spheres and morph extents of the culling bounds"));
    culler.mPhaseVisible = static_cast<std::uint32_t>(phaseVisible);

    const std::vector<std::uint32_t> arguments = argumentRecords(culler.mDraws);
    culler.mTrianglesDrawnWord = static_cast<std::uint32_t>(arguments.size() - 1);
    culler.mArguments = gpu::createStorageBuffer(
        device, arguments, "indirect arguments (all draws)",
        wgpu::BufferUsage::Indirect | wgpu::BufferUsage::CopySrc | wgpu::BufferUsage::CopyDst);
    culler.mVisible = gpu::createBuffer(device, wgpu::BufferUsage::Storage, visibleBytes,
                                        "visible instance lists and visibility");
    // Written whole before every first-phase cull (encodeFirstPhase).
    culler.mUniform =
        gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                          sizeof(CullingUniform), "culling uniform");

    std::vector<glm::uvec4> drawRecords =
        primitiveRecordsBySlot(culler.mDraws, records.primitives, culler.mBounds.slots);
    culler.mLevelBase = static_cast<std::uint32_t>(drawRecords.size());
    drawRecords.insert(drawRecords.end(), records.levels.begin(), records.levels.end());

    ENCORE_TRY_ASSIGN(const CullingPipelines pipelines,
                      createCullingPipelines(device, *setup.shaders));
    culler.mPyramidLayout = pipelines.pyramidLayout;
    culler.mReset = pipelines.reset;
    culler.mCullFirst = pipelines.cullFirst;
    culler.mCullSecond = pipelines.cullSecond;
    culler.bindCulling(pipelines.cullLayout, instances, animation, drawRecords,
                       arguments.size() * 4);
    culler.mDrawBindGroup =
        gpu::makeBindGroup(device, setup.layouts->culledInstances,
                           {{0, instances.buffer(), 0, instances.buffer().GetSize()},
                            {1, culler.mVisible, 0, listBytes}},
                           "culled instances");
    return culler;
}

void GpuCuller::bindCulling(const wgpu::BindGroupLayout& cullLayout,
                            const InstanceBuffer& instances,
                            const AnimationBuffers* animation,
                            std::span<const glm::uvec4> drawRecords,
                            std::uint64_t argumentBytes) {
    const wgpu::Device& device = mSetup->device;
    const std::vector<SlotBounds>& slots = mBounds.slots;
    const auto slotBuffer = gpu::createStorageBuffer(device, slots, "culling bounds");
    const auto shapeBuffer =
        gpu::createStorageBuffer(device, mBounds.shapes, "culling joint spheres");
    const auto recordBuffer =
        gpu::createStorageBuffer(device, drawRecords, "culled draws and levels");
    // A scene without skins or morph targets binds placeholders its records never index.
    wgpu::Buffer joints, weights;
    if (animation) {
        joints = animation->jointBuffer();
        weights = animation->weightBuffer();
    } else {
        joints = gpu::createBuffer(device, wgpu::BufferUsage::Storage, sizeof(glm::mat4) * 2,
                                   "no joints");
        weights = gpu::createBuffer(device, wgpu::BufferUsage::Storage, 16, "no morph weights");
    }
    mCullBindGroup = gpu::makeBindGroup(device, cullLayout,
                                        {{0, mUniform, 0, sizeof(CullingUniform)},
                                         {1, slotBuffer, 0, slots.size() * sizeof(SlotBounds)},
                                         {2, instances.buffer(), 0, instances.buffer().GetSize()},
                                         {3, shapeBuffer, 0, shapeBuffer.GetSize()},
                                         {4, recordBuffer, 0, drawRecords.size_bytes()},
                                         {5, mArguments, 0, argumentBytes},
                                         {6, mVisible, 0, mVisible.GetSize()},
                                         {7, joints, 0, joints.GetSize()},
                                         {8, weights, 0, weights.GetSize()}},
                                        "culling");
}

std::uint64_t submittedTriangles(std::span<const CulledDraw> draws) {
    std::uint64_t triangles = 0;
    for (const CulledDraw& draw : draws) {
        triangles += std::uint64_t(trianglesOf(draw, draw.elementCount)) * draw.instances.count;
    }
    return triangles;
}

void GpuCuller::encodeFirstPhase(const wgpu::Queue& queue,
                                 const wgpu::CommandEncoder& commands,
                                 const CullingView& view,
                                 gpu::GpuTimer* timer) {
    if (!mCullFirst) {
        return;
    }
    const Camera& camera = view.camera;
    const glm::mat4 viewProjection = camera.projection * camera.view;
    CullingUniform uniform;
    // One cull of several views serves every view, so it must keep what any of them sees. No
    // frustum rejects anything (views that frame the scene, as `render --views` and batch strips
    // do, each see all of it anyway), and levels of detail are chosen for the nearest view.
    fillCullingView(uniform, viewProjection, view.views.size() <= 1,
                    lodSelection(camera, view.views, view.targetHeight, view.options));
    uniform.occlusion = view.twoPhases ? 1u : 0u;
    uniform.viewport = glm::vec2(view.targetWidth, view.targetHeight);
    uniform.phaseArguments = mLevelDrawCount * 5;
    uniform.phaseVisible = mPhaseVisible;
    uniform.trianglesDrawnWord = mTrianglesDrawnWord;
    uniform.visibilityBase = mPhaseVisible * kPhases;
    uniform.levelBase = mLevelBase;
    queue.WriteBuffer(mUniform, 0, &uniform, sizeof(uniform));

    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "gpu culling (first phase)";
    descriptor.timestampWrites = timer ? timer->nextPass("culling (first phase)") : nullptr;
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    // Separate dispatches are separate usage scopes: the cull sees the reset's writes.
    pass.SetPipeline(mReset);
    pass.SetBindGroup(0, mCullBindGroup);
    pass.DispatchWorkgroups((mLevelDrawCount + kWorkgroupSize - 1) / kWorkgroupSize);
    pass.SetPipeline(mCullFirst);
    pass.SetBindGroup(0, mCullBindGroup);
    pass.DispatchWorkgroups((mSlotCount + kWorkgroupSize - 1) / kWorkgroupSize);
    pass.End();
}

void GpuCuller::encodeSecondPhase(const wgpu::CommandEncoder& commands,
                                  const wgpu::Texture& depth,
                                  gpu::GpuTimer* timer) {
    if (!mCullSecond) {
        return;
    }
    if (!mPyramid.builtFor(depth)) {
        auto pyramid = DepthPyramid::create(mSetup->device, *mSetup->shaders, depth);
        // The shader is embedded and the depth texture the renderer's own: a failure here is a
        // bug, not an input error.
        ENCORE_CHECK(pyramid.ok(), "the depth pyramid cannot be built: " + pyramid.error().message);
        mPyramid = std::move(*pyramid);
        mPyramidBindGroup = gpu::makeBindGroup(mSetup->device, mPyramidLayout,
                                               {{0, mPyramid.view()}}, "culling depth pyramid");
    }
    // One pass: each dispatch is its own usage scope, so the cull reads the finished pyramid.
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "depth pyramid and gpu culling (second phase)";
    descriptor.timestampWrites =
        timer ? timer->nextPass("depth pyramid and culling (second phase)") : nullptr;
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    mPyramid.encode(pass);
    pass.SetPipeline(mCullSecond);
    pass.SetBindGroup(0, mCullBindGroup);
    pass.SetBindGroup(1, mPyramidBindGroup);
    pass.DispatchWorkgroups((mSlotCount + kWorkgroupSize - 1) / kWorkgroupSize);
    pass.End();
}

}  // namespace encore::render
