#include "render/animation/GpuAnimation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "gpu/BindingResource.h"
#include "gpu/Upload.h"
#include "render/AnimationBuffers.h"
#include "render/BindGroupLayouts.h"
#include "render/animation/AnimationTables.h"

namespace encore::render {

namespace {

using gpu::createStorageBuffer;

constexpr std::uint32_t kNone = kNoAnimationIndex;
constexpr std::uint32_t kWorkgroupSize = kAnimationWorkgroupSize;

std::uint32_t workgroups(std::uint32_t threads) {
    return (threads + kWorkgroupSize - 1) / kWorkgroupSize;
}

// A bind group of the layout WebGPU derived from the pipeline's shader.
wgpu::BindGroup pipelineBindGroup(const wgpu::Device& device,
                                  const wgpu::ComputePipeline& pipeline,
                                  std::initializer_list<gpu::BindingResource> resources,
                                  const char* label) {
    return gpu::makeBindGroup(device, pipeline.GetBindGroupLayout(0), resources, label);
}

Result<wgpu::ComputePipeline> makePipeline(const wgpu::Device& device,
                                           shaders::ShaderLibrary& shaders,
                                           const char* file,
                                           const char* entryPoint) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module(file));
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.label = entryPoint;
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = entryPoint;
    return device.CreateComputePipeline(&descriptor);
}

}  // namespace

std::string_view animationEvaluationName(AnimationEvaluation evaluation) {
    return evaluation == AnimationEvaluation::Gpu ? "gpu" : "cpu";
}

std::optional<AnimationEvaluation> animationEvaluationFromName(std::string_view name) {
    if (name == "cpu") {
        return AnimationEvaluation::Cpu;
    }
    if (name == "gpu") {
        return AnimationEvaluation::Gpu;
    }
    return std::nullopt;
}

Result<void> GpuAnimation::checkLimits(const gpu::DeviceLimits& limits,
                                       const scene::SceneData& scene) {
    return checkAnimationTables(limits, scene);
}

Result<std::unique_ptr<GpuAnimation>> GpuAnimation::create(
    const wgpu::Device& device,
    const wgpu::Queue& queue,
    shaders::ShaderLibrary& shaders,
    const gpu::DeviceLimits& limits,
    const scene::SceneData& scene,
    const AnimationBuffers* animation,
    const InstanceTransformTargets& instances) {
    if (scene.animations.empty()) {
        return std::unique_ptr<GpuAnimation>();
    }
    // Joint matrices go to AnimationBuffers' joint buffer: none without.
    ENCORE_TRY_ASSIGN(AnimationTables tables,
                      buildAnimationTables(limits, scene, instances.slots, animation != nullptr));
    auto result = std::unique_ptr<GpuAnimation>(new GpuAnimation());
    GpuAnimation& gpu = *result;
    gpu.mScene = &scene;
    gpu.mSamplerOffsets = std::move(tables.firstSampler);
    gpu.mClockEnds = std::move(tables.clockEnds);
    gpu.keepIndices(tables);
    gpu.countStats(tables);

    gpu.createNodeMatrices(device, scene);
    ENCORE_TRY(gpu.createPipelines(device, shaders));
    gpu.bindSampling(device, tables, animation);
    gpu.bindWorldLevels(device, limits, tables);
    gpu.bindTransforms(device, tables, animation, instances);

    std::vector<scene::AnimationId> all;
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        all.push_back(scene::AnimationId(a));
    }
    gpu.select(queue, all);
    return result;
}

void GpuAnimation::keepIndices(const AnimationTables& tables) {
    for (const NodeRecord& record : tables.nodes) {
        mAnimatedNodes.push_back(record.node);
    }
    for (const glm::uvec4& range : tables.world.ranges) {
        mLevelCounts.push_back(range.y);
    }
    mInstances = tables.instances.sceneInstances;
    for (const TransformRecord& record : tables.instances.records) {
        mInstanceSlots.push_back(record.slot);
    }
    mInstanceRecords = static_cast<std::uint32_t>(tables.instances.records.size());
    mJointRecords = static_cast<std::uint32_t>(tables.joints.size());
}

void GpuAnimation::countStats(const AnimationTables& tables) {
    GpuAnimationStats& stats = mStats;
    stats.animatedNodes = static_cast<std::uint32_t>(tables.nodes.size());
    stats.worldNodes = static_cast<std::uint32_t>(tables.world.records.size());
    stats.levels = static_cast<std::uint32_t>(tables.world.ranges.size());
    stats.instances = mInstanceRecords;
    stats.joints = mJointRecords;
    stats.dispatches = (stats.animatedNodes ? 1 : 0) + stats.levels + (stats.instances ? 1 : 0) +
                       (stats.joints ? 1 : 0);
    stats.copies = static_cast<std::uint32_t>(mCopyTargets.size());
    stats.bytesPerFrame = mClockEnds.size() * sizeof(float);
    stats.clocks = static_cast<std::uint32_t>(mClockEnds.size());
    stats.keyframeBytes = tables.keyframes.size() * sizeof(float);
}

void GpuAnimation::createNodeMatrices(const wgpu::Device& device, const scene::SceneData& scene) {
    const std::size_t nodeCount = scene.nodes.size();
    std::vector<glm::mat4> restLocals(nodeCount), restWorlds(nodeCount);
    for (std::size_t n = 0; n < nodeCount; ++n) {
        restLocals[n] = scene.nodes[n].local;
        restWorlds[n] = scene.nodes[n].world;
    }
    const auto readable = wgpu::BufferUsage::CopySrc | wgpu::BufferUsage::CopyDst;
    mLocals = createStorageBuffer(device, std::move(restLocals), "animated node locals", readable);
    mWorlds = createStorageBuffer(device, std::move(restWorlds), "animated node worlds", readable);
}

// The pipelines of the three passes, each with the layout WebGPU derives from its shader.
Result<void> GpuAnimation::createPipelines(const wgpu::Device& device,
                                           shaders::ShaderLibrary& shaders) {
    auto sample = makePipeline(device, shaders, "animation_sample.wgsl", "sampleNodes");
    auto world = makePipeline(device, shaders, "animation_world.wgsl", "worldMatrices");
    auto transform = makePipeline(device, shaders, "animation_transforms.wgsl", "nodeTransforms");
    if (!sample || !world || !transform) {
        return !sample ? sample.error() : !world ? world.error() : transform.error();
    }
    mSample = *sample;
    mWorld = *world;
    mTransform = *transform;
    return {};
}

// Pass 1 reads the keyframes (taken from `tables`), samplers, clocks and node records, and
// writes the node locals and the morph weights.
void GpuAnimation::bindSampling(const wgpu::Device& device,
                                AnimationTables& tables,
                                const AnimationBuffers* animation) {
    std::vector<float> keyframeFloats = tables.keyframes.take();
    if (keyframeFloats.empty()) {
        keyframeFloats.push_back(0.0f);  // No zero-sized bindings.
    }
    const wgpu::Buffer keyframeBuffer =
        createStorageBuffer(device, std::move(keyframeFloats), "keyframes");
    const wgpu::Buffer samplerBuffer =
        createStorageBuffer(device, std::move(tables.samplers), "samplers");
    const wgpu::Buffer animationBuffer =
        createStorageBuffer(device, std::move(tables.animations), "animation clocks");
    const wgpu::Buffer nodeBuffer = createStorageBuffer(device, tables.nodes, "animated nodes");
    mClockTimes.assign(1 + mClockEnds.size(), 0.0f);
    mClocks = createStorageBuffer(device, mClockTimes, "animation clock times",
                                  wgpu::BufferUsage::CopyDst);
    mNodeChannels =
        createStorageBuffer(device, std::vector<glm::uvec4>(tables.nodes.size(), glm::uvec4(kNone)),
                            "animated node channels", wgpu::BufferUsage::CopyDst);
    wgpu::Buffer weights = animation ? animation->weightBuffer() : wgpu::Buffer();
    if (!weights) {
        weights = createStorageBuffer(device, std::vector<float>(1, 0.0f), "no morph weights");
    }
    mSampleGroup = pipelineBindGroup(device, mSample,
                                     {{0, keyframeBuffer},
                                      {1, samplerBuffer},
                                      {2, mClocks},
                                      {3, nodeBuffer},
                                      {4, mNodeChannels},
                                      {5, mLocals},
                                      {6, weights},
                                      {7, animationBuffer}},
                                     "animation sampling");
}

// Pass 2 dispatches once per level, each with its range of the world records at a uniform
// offset.
void GpuAnimation::bindWorldLevels(const wgpu::Device& device,
                                   const gpu::DeviceLimits& limits,
                                   const AnimationTables& tables) {
    const std::vector<glm::uvec4>& levelRanges = tables.world.ranges;
    const std::uint64_t levelStride =
        std::max<std::uint64_t>(limits.minUniformBufferOffsetAlignment, sizeof(glm::uvec4));
    std::vector<std::uint8_t> levelBytes(std::max<std::size_t>(1, levelRanges.size()) * levelStride,
                                         0);
    for (std::size_t l = 0; l < levelRanges.size(); ++l) {
        std::memcpy(levelBytes.data() + l * levelStride, &levelRanges[l], sizeof(glm::uvec4));
    }
    const wgpu::Buffer levelBuffer =
        gpu::createBufferWithData(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                  levelBytes, "world levels ranges");
    const wgpu::Buffer worldBuffer =
        createStorageBuffer(device, tables.world.records, "world levels");
    for (std::size_t l = 0; l < levelRanges.size(); ++l) {
        mLevelGroups.push_back(
            pipelineBindGroup(device, mWorld,
                              {{0, levelBuffer, l * levelStride, sizeof(glm::uvec4)},
                               {1, worldBuffer},
                               {2, mLocals},
                               {3, mWorlds}},
                              "world level"));
    }
}

// Pass 3 writes the moved instances' transforms into the GPU scene's instance transforms and
// the moved joints' matrices into AnimationBuffers' joint buffer.
void GpuAnimation::bindTransforms(const wgpu::Device& device,
                                  const AnimationTables& tables,
                                  const AnimationBuffers* animation,
                                  const InstanceTransformTargets& instances) {
    const wgpu::Buffer instanceBuffer =
        createStorageBuffer(device, tables.instances.records, "animated instance records");
    const wgpu::Buffer jointBuffer =
        createStorageBuffer(device, tables.joints, "animated joint records");
    mInstanceOutput = instances.storage;
    if (!tables.instances.records.empty()) {
        mInstanceGroup = pipelineBindGroup(
            device, mTransform, {{0, instanceBuffer}, {1, mWorlds}, {2, mInstanceOutput}},
            "animated instances");
    }
    if (!tables.joints.empty()) {
        mJointGroup = pipelineBindGroup(
            device, mTransform, {{0, jointBuffer}, {1, mWorlds}, {2, animation->jointBuffer()}},
            "animated joints");
    }
}

void GpuAnimation::select(const wgpu::Queue& queue, std::span<const scene::AnimationId> selection) {
    if (mAnimatedNodes.empty()) {
        return;
    }
    std::vector<std::uint32_t> slotOfNode(mScene->nodes.size(), kNone);
    for (std::size_t i = 0; i < mAnimatedNodes.size(); ++i) {
        slotOfNode[mAnimatedNodes[i]] = static_cast<std::uint32_t>(i);
    }
    std::vector<glm::uvec4> channels(mAnimatedNodes.size(), glm::uvec4(kNone));
    for (const scene::AnimationId id : selection) {
        const scene::Animation& animation = mScene->animations[id.index()];
        for (const scene::AnimationChannel& channel : animation.channels) {
            const std::uint32_t slot = slotOfNode[channel.node.index()];
            channels[slot][static_cast<int>(channel.path)] =
                mSamplerOffsets[id.index()] + channel.sampler;
        }
    }
    queue.WriteBuffer(mNodeChannels, 0, channels.data(), channels.size() * sizeof(glm::uvec4));
}

void GpuAnimation::setTime(const wgpu::Queue& queue, double seconds, scene::PlaybackMode mode) {
    for (std::size_t c = 0; c < mClockEnds.size(); ++c) {
        mClockTimes[1 + c] = static_cast<float>(scene::playbackTime(seconds, mClockEnds[c], mode));
    }
    // The header (the playback mode) only when it changes: a frame writes one float per clock.
    const float loopFlag = mode == scene::PlaybackMode::Loop ? 1.0f : 0.0f;
    const bool modeChanged = !mModeWritten || mClockTimes[0] != loopFlag;
    mClockTimes[0] = loopFlag;
    mModeWritten = true;
    const std::size_t first = modeChanged ? 0 : 1;
    if (mClockTimes.size() > first) {
        queue.WriteBuffer(mClocks, first * sizeof(float), mClockTimes.data() + first,
                          (mClockTimes.size() - first) * sizeof(float));
    }
}

void GpuAnimation::encode(const wgpu::CommandEncoder& commands) const {
    wgpu::ComputePassDescriptor descriptor{};
    descriptor.label = "animation";
    wgpu::ComputePassEncoder pass = commands.BeginComputePass(&descriptor);
    if (!mAnimatedNodes.empty()) {
        pass.SetPipeline(mSample);
        pass.SetBindGroup(0, mSampleGroup);
        pass.DispatchWorkgroups(workgroups(static_cast<std::uint32_t>(mAnimatedNodes.size())));
    }
    if (!mLevelGroups.empty()) {
        pass.SetPipeline(mWorld);
        for (std::size_t l = 0; l < mLevelGroups.size(); ++l) {
            pass.SetBindGroup(0, mLevelGroups[l]);
            pass.DispatchWorkgroups(workgroups(mLevelCounts[l]));
        }
    }
    if (mInstanceRecords > 0 || mJointRecords > 0) {
        pass.SetPipeline(mTransform);
        if (mInstanceRecords > 0) {
            pass.SetBindGroup(0, mInstanceGroup);
            pass.DispatchWorkgroups(workgroups(mInstanceRecords));
        }
        if (mJointRecords > 0) {
            pass.SetBindGroup(0, mJointGroup);
            pass.DispatchWorkgroups(workgroups(mJointRecords));
        }
    }
    pass.End();
    for (std::size_t k = 0; k < mCopyTargets.size(); ++k) {
        const std::uint64_t slot = mInstanceSlots[k];
        commands.CopyBufferToBuffer(mInstanceOutput, slot * sizeof(TransformUniform),
                                    mCopyTargets[k], 0, sizeof(TransformUniform));
    }
}

void GpuAnimation::copyInstancesTo(std::span<const wgpu::Buffer> uniforms) {
    mCopyTargets.clear();
    if (!uniforms.empty()) {
        for (std::uint32_t instance : mInstances) {
            mCopyTargets.push_back(uniforms[instance]);
        }
    }
    mStats.copies = static_cast<std::uint32_t>(mCopyTargets.size());
}

}  // namespace encore::render
