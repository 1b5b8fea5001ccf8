#include "encore/render/GpuCuller.h"

#include <algorithm>
#include <map>
#include <numeric>

#include "encore/gpu/BindGroupEntries.h"
#include "encore/gpu/Upload.h"
#include "encore/render/AnimationBuffers.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;          // culling.wgsl's kWorkgroupSize.
constexpr std::uint32_t kVisibleAlignmentEntries = 64;  // 256 bytes: storage offset alignment.

struct DrawRecord {
    std::uint32_t visibleBase;
    std::uint32_t argumentsOffset;  // In u32 words.
    std::uint32_t triangles;        // Per instance, for the drawn-triangle count.
};

// Every culling buffer is bound whole as storage. The per-draw buffer checked is the largest of
// its kind (20 bytes of indirect arguments per draw).
Result<void> checkCullingBuffers(const gpu::DeviceLimits& limits, std::size_t drawCount,
                                 std::uint32_t slotCount, std::uint64_t visibleBytes) {
    const std::string draws = std::to_string(drawCount) + " culled draws";
    const std::string slots = std::to_string(slotCount) + " instances";
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(drawCount) * 5 * 4 + 4,
                                        "The indirect draw arguments of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(drawCount) * sizeof(DrawRecord),
                                        "The culling records of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(slotCount) * sizeof(SlotBounds),
                                        "The culling bounds of " + slots));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, visibleBytes,
        "The visible-instance lists of " + draws + " over " + slots +
            " (one list per draw, as long as its instance count, rounded to 64 entries)"));
    return {};
}

}  // namespace

std::uint64_t submittedTriangles(std::span<const CulledDraw> draws) {
    std::uint64_t triangles = 0;
    for (const CulledDraw& draw : draws) {
        triangles += std::uint64_t(draw.triangles) * draw.instances.count;
    }
    return triangles;
}

Result<GpuCuller> GpuCuller::create(const RenderSetup& setup, const InstanceBuffer& instances,
                                    CullingBounds bounds, std::vector<CulledDraw> draws) {
    GpuCuller culler;
    culler.mDraws = std::move(draws);
    culler.mBounds = std::move(bounds);
    culler.mSlotCount = static_cast<std::uint32_t>(culler.mBounds.slots.size());
    if (culler.mDraws.empty() || culler.mSlotCount == 0) {
        return culler;  // Nothing to cull: encode() does nothing.
    }
    const wgpu::Device& device = setup.device;

    // Arguments: instanceCount starts at 0; the first cull pass fills it.
    std::vector<std::uint32_t> arguments;
    // 64 bits until checked: thousands of primitives of a million instances pass 2^32 entries.
    std::uint64_t nextBase = 0;
    std::uint64_t lastBase = 0;
    std::uint32_t largestList = 1;
    for (const CulledDraw& draw : culler.mDraws) {
        // drawIndexedIndirect reads five words (count, instances, first index, base vertex,
        // first instance), drawIndirect the first four; one record layout serves both.
        arguments.insert(arguments.end(), {draw.elementCount, 0, 0, 0, 0});
        culler.mVisibleBase.push_back(static_cast<std::uint32_t>(nextBase));
        lastBase = nextBase;
        const std::uint32_t capacity = std::max(draw.instances.count, 1u);
        largestList = std::max(largestList, capacity);
        nextBase += (std::uint64_t(capacity) + kVisibleAlignmentEntries - 1) /
                    kVisibleAlignmentEntries * kVisibleAlignmentEntries;
    }
    arguments.push_back(0);  // The drawn-triangle count (drawnTrianglesOffset).
    const std::uint64_t listBytes = std::uint64_t(largestList) * 4;
    const std::uint64_t visibleBytes = lastBase * 4 + listBytes;
    ENCORE_TRY(checkCullingBuffers(setup.limits, culler.mDraws.size(), culler.mSlotCount,
                                   visibleBytes));
    culler.mArguments = gpu::createStorageBuffer(device, arguments, "indirect arguments (all draws)",
                                      wgpu::BufferUsage::Indirect | wgpu::BufferUsage::CopySrc |
                                          wgpu::BufferUsage::CopyDst);
    culler.mVisible = gpu::createBuffer(device, wgpu::BufferUsage::Storage, visibleBytes,
                                        "visible instance lists");

    // Each slot lists the culled draws of its instance range, contiguous in `draws`; slots whose
    // mesh has no culled draw (all its primitives blended) list none.
    std::map<std::uint32_t, std::vector<std::uint32_t>> drawsOfRange;  // By first slot.
    for (std::uint32_t i = 0; i < culler.mDraws.size(); ++i) {
        drawsOfRange[culler.mDraws[i].instances.first].push_back(i);
    }
    std::vector<DrawRecord> drawRecords;
    std::vector<SlotBounds>& slots = culler.mBounds.slots;
    for (const auto& [firstSlot, drawIndices] : drawsOfRange) {
        const auto firstDraw = static_cast<std::uint32_t>(drawRecords.size());
        for (std::uint32_t draw : drawIndices) {
            drawRecords.push_back(
                {culler.mVisibleBase[draw], draw * 5, culler.mDraws[draw].triangles});
        }
        const InstanceRange range = culler.mDraws[drawIndices.front()].instances;
        for (std::uint32_t slot = range.first; slot < range.first + range.count; ++slot) {
            slots[slot].firstDraw = firstDraw;
            slots[slot].drawCount = static_cast<std::uint32_t>(drawIndices.size());
        }
    }

    culler.mFrustum = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                        sizeof(glm::vec4) * 6, "frustum planes");
    const auto slotBuffer = gpu::createStorageBuffer(device, slots, "culling bounds");
    ENCORE_TRY(gpu::checkStorageBinding(
        setup.limits, culler.mBounds.shapes.size() * sizeof(glm::vec4),
        "The joint spheres and morph extents of the culling bounds"));
    const auto shapeBuffer =
        gpu::createStorageBuffer(device, culler.mBounds.shapes, "culling joint spheres");
    const auto drawBuffer = gpu::createStorageBuffer(device, drawRecords, "culled draws");
    // A scene without skins or morph targets binds placeholders its records never index.
    wgpu::Buffer joints, weights;
    if (setup.animation) {
        joints = setup.animation->jointBuffer();
        weights = setup.animation->weightBuffer();
    } else {
        joints = gpu::createBuffer(device, wgpu::BufferUsage::Storage, sizeof(glm::mat4) * 2,
                                   "no joints");
        weights = gpu::createBuffer(device, wgpu::BufferUsage::Storage, 16, "no morph weights");
    }

    auto module = setup.shaders->module("culling.wgsl");
    if (!module) {
        return module.error();
    }
    // One explicit layout for both entry points: layouts derived from each shader entry point
    // would be distinct and their bind groups incompatible.
    auto layoutEntry = [](std::uint32_t binding, wgpu::BufferBindingType type) {
        wgpu::BindGroupLayoutEntry entry{};
        entry.binding = binding;
        entry.visibility = wgpu::ShaderStage::Compute;
        entry.buffer.type = type;
        return entry;
    };
    using Type = wgpu::BufferBindingType;
    const wgpu::BindGroupLayoutEntry layoutEntries[] = {
        layoutEntry(0, Type::Uniform),         layoutEntry(1, Type::ReadOnlyStorage),
        layoutEntry(2, Type::ReadOnlyStorage), layoutEntry(3, Type::ReadOnlyStorage),
        layoutEntry(4, Type::ReadOnlyStorage), layoutEntry(5, Type::Storage),
        layoutEntry(6, Type::Storage),         layoutEntry(7, Type::ReadOnlyStorage),
        layoutEntry(8, Type::ReadOnlyStorage)};
    wgpu::BindGroupLayoutDescriptor layoutDescriptor{};
    layoutDescriptor.label = "culling";
    layoutDescriptor.entryCount = std::size(layoutEntries);
    layoutDescriptor.entries = layoutEntries;
    const wgpu::BindGroupLayout cullLayout = device.CreateBindGroupLayout(&layoutDescriptor);
    wgpu::PipelineLayoutDescriptor pipelineLayoutDescriptor{};
    pipelineLayoutDescriptor.bindGroupLayoutCount = 1;
    pipelineLayoutDescriptor.bindGroupLayouts = &cullLayout;
    const wgpu::PipelineLayout pipelineLayout =
        device.CreatePipelineLayout(&pipelineLayoutDescriptor);
    auto computePipeline = [&](const char* entryPoint) {
        wgpu::ComputePipelineDescriptor descriptor{};
        descriptor.label = entryPoint;
        descriptor.layout = pipelineLayout;
        descriptor.compute.module = *module;
        descriptor.compute.entryPoint = entryPoint;
        return device.CreateComputePipeline(&descriptor);
    };
    culler.mReset = computePipeline("resetCounts");
    culler.mCull = computePipeline("cullInstances");

    const wgpu::BindGroupEntry cullEntries[] = {
        gpu::bufferEntry(0, culler.mFrustum, 0, sizeof(glm::vec4) * 6),
        gpu::bufferEntry(1, slotBuffer, 0, slots.size() * sizeof(SlotBounds)),
        gpu::bufferEntry(2, instances.buffer(), 0, instances.buffer().GetSize()),
        gpu::bufferEntry(3, shapeBuffer, 0, shapeBuffer.GetSize()),
        gpu::bufferEntry(4, drawBuffer, 0, drawRecords.size() * sizeof(DrawRecord)),
        gpu::bufferEntry(5, culler.mArguments, 0, arguments.size() * 4),
        gpu::bufferEntry(6, culler.mVisible, 0, culler.mVisible.GetSize()),
        gpu::bufferEntry(7, joints, 0, joints.GetSize()),
        gpu::bufferEntry(8, weights, 0, weights.GetSize()),
    };
    wgpu::BindGroupDescriptor cullDescriptor{};
    cullDescriptor.label = "culling";
    cullDescriptor.layout = cullLayout;
    cullDescriptor.entryCount = std::size(cullEntries);
    cullDescriptor.entries = cullEntries;
    culler.mCullBindGroup = device.CreateBindGroup(&cullDescriptor);

    const wgpu::BindGroupEntry drawEntries[] = {
        gpu::bufferEntry(0, instances.buffer(), 0, instances.buffer().GetSize()),
        gpu::bufferEntry(1, culler.mVisible, 0, listBytes),
    };
    wgpu::BindGroupDescriptor drawDescriptor{};
    drawDescriptor.label = "culled instances";
    drawDescriptor.layout = setup.layouts->culledInstances;
    drawDescriptor.entryCount = std::size(drawEntries);
    drawDescriptor.entries = drawEntries;
    culler.mDrawBindGroup = device.CreateBindGroup(&drawDescriptor);
    return culler;
}

void GpuCuller::encode(const wgpu::Queue& queue, const wgpu::CommandEncoder& commands,
                       const Camera& camera, gpu::GpuTimer* timer) const {
    if (!mCull) {
        return;
    }
    const Frustum frustum = Frustum::fromViewProjection(camera.projection * camera.view);
    queue.WriteBuffer(mFrustum, 0, frustum.planes.data(), sizeof(frustum.planes));
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "gpu culling";
    descriptor.timestampWrites = timer ? timer->nextPass() : nullptr;
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    // Separate dispatches are separate usage scopes: the cull sees the reset's writes.
    pass.SetPipeline(mReset);
    pass.SetBindGroup(0, mCullBindGroup);
    pass.DispatchWorkgroups((static_cast<std::uint32_t>(mDraws.size()) + kWorkgroupSize - 1) /
                            kWorkgroupSize);
    pass.SetPipeline(mCull);
    pass.SetBindGroup(0, mCullBindGroup);
    pass.DispatchWorkgroups((mSlotCount + kWorkgroupSize - 1) / kWorkgroupSize);
    pass.End();
}

}  // namespace encore::render
