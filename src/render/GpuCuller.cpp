#include "encore/render/GpuCuller.h"

#include <algorithm>
#include <map>
#include <numeric>

#include "encore/gpu/BindGroupEntries.h"
#include "encore/gpu/Upload.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;          // culling.wgsl's kWorkgroupSize.
constexpr std::uint32_t kVisibleAlignmentEntries = 64;  // 256 bytes: storage offset alignment.

struct RangeRecord {
    std::uint32_t firstDraw;
    std::uint32_t drawCount;
};
struct DrawRecord {
    std::uint32_t visibleBase;
    std::uint32_t argumentsOffset;  // In u32 words.
};

// Every culling buffer is bound whole as storage. The per-draw and per-slot buffers checked are
// the largest of their kind (20 bytes of indirect arguments per draw, a 16-byte sphere per
// slot); the instance ranges and each slot's range are smaller.
Result<void> checkCullingBuffers(const gpu::DeviceLimits& limits, std::size_t drawCount,
                                 std::uint32_t slotCount, std::uint64_t visibleBytes) {
    const std::string draws = std::to_string(drawCount) + " culled draws";
    const std::string slots = std::to_string(slotCount) + " instances";
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(drawCount) * 5 * 4,
                                        "The indirect draw arguments of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(drawCount) * sizeof(DrawRecord),
                                        "The culling records of " + draws));
    ENCORE_TRY(gpu::checkStorageBinding(limits, std::uint64_t(slotCount) * sizeof(Sphere),
                                        "The bounding spheres of " + slots));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, visibleBytes,
        "The visible-instance lists of " + draws + " over " + slots +
            " (one list per draw, as long as its instance count, rounded to 64 entries)"));
    return {};
}

}  // namespace

Result<GpuCuller> GpuCuller::create(const RenderSetup& setup, const InstanceBuffer& instances,
                                    std::vector<Sphere> spheres, std::vector<CulledDraw> draws) {
    GpuCuller culler;
    culler.mDraws = std::move(draws);
    culler.mSpheres = std::move(spheres);
    culler.mSlotCount = static_cast<std::uint32_t>(culler.mSpheres.size());
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
    const std::uint64_t listBytes = std::uint64_t(largestList) * 4;
    const std::uint64_t visibleBytes = lastBase * 4 + listBytes;
    ENCORE_TRY(checkCullingBuffers(setup.limits, culler.mDraws.size(), culler.mSlotCount,
                                   visibleBytes));
    culler.mArguments = gpu::createStorageBuffer(device, arguments, "indirect arguments (all draws)",
                                      wgpu::BufferUsage::Indirect | wgpu::BufferUsage::CopySrc |
                                          wgpu::BufferUsage::CopyDst);
    culler.mVisible = gpu::createBuffer(device, wgpu::BufferUsage::Storage, visibleBytes,
                                        "visible instance lists");

    // Draws grouped by instance range, for the per-instance loop of cullInstances. Range 0 is
    // empty: slots whose mesh has no culled draw (all its primitives blended) point there.
    std::map<std::uint32_t, std::vector<std::uint32_t>> drawsOfRange;  // By first slot.
    for (std::uint32_t i = 0; i < culler.mDraws.size(); ++i) {
        drawsOfRange[culler.mDraws[i].instances.first].push_back(i);
    }
    std::vector<RangeRecord> ranges = {{0, 0}};
    std::vector<DrawRecord> drawRecords;
    std::vector<std::uint32_t> rangeOfSlot(culler.mSlotCount, 0);
    for (const auto& [firstSlot, drawIndices] : drawsOfRange) {
        const auto rangeIndex = static_cast<std::uint32_t>(ranges.size());
        ranges.push_back({static_cast<std::uint32_t>(drawRecords.size()),
                          static_cast<std::uint32_t>(drawIndices.size())});
        for (std::uint32_t draw : drawIndices) {
            drawRecords.push_back({culler.mVisibleBase[draw], draw * 5});
        }
        const InstanceRange range = culler.mDraws[drawIndices.front()].instances;
        std::fill(rangeOfSlot.begin() + range.first, rangeOfSlot.begin() + range.first + range.count,
                  rangeIndex);
    }

    culler.mFrustum = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                        sizeof(glm::vec4) * 6, "frustum planes");
    culler.mSphereBuffer = gpu::createStorageBuffer(device, culler.mSpheres, "instance bounding spheres",
                                         wgpu::BufferUsage::CopyDst);
    const auto rangeOfSlotBuffer = gpu::createStorageBuffer(device, rangeOfSlot, "range of each slot");
    const auto rangeBuffer = gpu::createStorageBuffer(device, ranges, "instance ranges");
    const auto drawBuffer = gpu::createStorageBuffer(device, drawRecords, "culled draws");

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
        layoutEntry(6, Type::Storage)};
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
        gpu::bufferEntry(1, culler.mSphereBuffer, 0, culler.mSpheres.size() * sizeof(Sphere)),
        gpu::bufferEntry(2, rangeOfSlotBuffer, 0, rangeOfSlot.size() * 4),
        gpu::bufferEntry(3, rangeBuffer, 0, ranges.size() * sizeof(RangeRecord)),
        gpu::bufferEntry(4, drawBuffer, 0, drawRecords.size() * sizeof(DrawRecord)),
        gpu::bufferEntry(5, culler.mArguments, 0, arguments.size() * 4),
        gpu::bufferEntry(6, culler.mVisible, 0, culler.mVisible.GetSize()),
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

void GpuCuller::updateSphere(const wgpu::Queue& queue, std::uint32_t slot, const Sphere& sphere) {
    if (slot >= mSpheres.size() || !mSphereBuffer) {
        return;
    }
    mSpheres[slot] = sphere;
    queue.WriteBuffer(mSphereBuffer, std::uint64_t(slot) * sizeof(Sphere), &sphere, sizeof(sphere));
}

}  // namespace encore::render
