// GPU-evaluated animation: the tables the compute passes read are built here once, from the
// SceneData alone, in the same orders AnimationPlayer uses (node weights node after node, joints
// skin after skin), so that the passes write where the CPU path writes.

#include "render/animation/GpuAnimation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "gpu/BindingResource.h"
#include "gpu/Upload.h"
#include "render/AnimationBuffers.h"
#include "render/BindGroupLayouts.h"
#include "render/animation/KeyframeStore.h"

namespace encore::render {

namespace {

using gpu::createStorageBuffer;

constexpr std::uint32_t kNone = 0xFFFFFFFFu;
constexpr std::uint32_t kWorkgroupSize = 64;     // kWorkgroupSize of the animation_*.wgsl shaders.
constexpr std::uint64_t kMaxWorkgroups = 65535;  // maxComputeWorkgroupsPerDimension (default).

// animation_sample.wgsl's Sampler.
struct SamplerRecord {
    std::uint32_t timesOffset;
    std::uint32_t keyCount;
    std::uint32_t valuesOffset;
    std::uint32_t components;
    std::uint32_t interpolation;  // 0 STEP, 1 LINEAR, 2 CUBICSPLINE.
    std::uint32_t animation;
    std::uint32_t pad[2];
};
static_assert(sizeof(SamplerRecord) == 32);

// animation_sample.wgsl's AnimationClock.
struct AnimationRecord {
    std::uint32_t clock;
    float offset;
    float wrappedOffset;
    float end;
};
static_assert(sizeof(AnimationRecord) == 16);

// animation_sample.wgsl's AnimatedNode.
struct NodeRecord {
    glm::mat4 restLocal;
    glm::vec4 translation;
    glm::vec4 rotation;  // x, y, z, w.
    glm::vec4 scale;
    std::uint32_t node;
    std::uint32_t weightOffset;
    std::uint32_t weightCount;
    std::uint32_t restWeights;
};
static_assert(sizeof(NodeRecord) == 128);

// animation_world.wgsl's WorldNode.
struct WorldRecord {
    std::uint32_t node;
    std::uint32_t parent;
};

// animation_transforms.wgsl's Record.
struct TransformRecord {
    std::uint32_t node;
    std::uint32_t slot;
    std::uint32_t pad[2];
    glm::mat4 transform;
};
static_assert(sizeof(TransformRecord) == 80);

std::uint32_t interpolationCode(scene::Interpolation interpolation) {
    switch (interpolation) {
        case scene::Interpolation::Step:
            return 0;
        case scene::Interpolation::Linear:
            return 1;
        case scene::Interpolation::CubicSpline:
            return 2;
    }
    return 1;
}

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

// The offset of each node's weights in AnimationPlayer::morphWeights() (kNone without).
std::vector<std::uint32_t> weightOffsets(const scene::SceneData& scene) {
    std::vector<std::uint32_t> offsets(scene.nodes.size(), kNone);
    std::uint32_t next = 0;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (!scene.nodes[n].weights.empty()) {
            offsets[n] = next;
            next += static_cast<std::uint32_t>(scene.nodes[n].weights.size());
        }
    }
    return offsets;
}

// Every sampler's times and values, shared where equal; the records point into the store.
struct SamplerLayout {
    KeyframeStore keyframes;
    std::vector<SamplerRecord> samplers;
    std::vector<std::uint32_t> firstSampler;  // Per animation.
};

SamplerLayout layoutSamplers(const scene::SceneData& scene) {
    SamplerLayout layout;
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        layout.firstSampler.push_back(static_cast<std::uint32_t>(layout.samplers.size()));
        for (const scene::AnimationSampler& sampler : scene.animations[a].samplers) {
            SamplerRecord record{};
            record.timesOffset = layout.keyframes.add(sampler.times);
            record.keyCount = static_cast<std::uint32_t>(sampler.times.size());
            record.valuesOffset = layout.keyframes.add(sampler.values);
            record.components = sampler.components;
            record.interpolation = interpolationCode(sampler.interpolation);
            record.animation = static_cast<std::uint32_t>(a);
            layout.samplers.push_back(record);
        }
    }
    return layout;
}

std::uint64_t restWeightFloats(const scene::SceneData& scene) {
    std::uint64_t floats = 0;
    for (const scene::Node& node : scene.nodes) {
        floats += node.weights.size();
    }
    return floats;
}

// One clock per distinct duration, in order of first use; `clockOf` gets each animation's clock.
std::vector<float> animationClocks(const scene::SceneData& scene,
                                   std::vector<std::uint32_t>& clockOf) {
    std::vector<float> ends;
    std::unordered_map<float, std::uint32_t> clockOfEnd;
    for (const scene::Animation& animation : scene.animations) {
        auto [it, inserted] =
            clockOfEnd.emplace(animation.end, static_cast<std::uint32_t>(ends.size()));
        if (inserted) {
            ends.push_back(animation.end);
        }
        clockOf.push_back(it->second);
    }
    return ends;
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

namespace {

// GpuAnimation::checkLimits, given the keyframe floats that the scene stores once shared.
Result<void> checkSizes(const gpu::DeviceLimits& limits,
                        const scene::SceneData& scene,
                        std::uint64_t keyframeFloats) {
    const std::uint64_t nodes = scene.nodes.size();
    std::uint64_t samplers = 0;
    for (const scene::Animation& animation : scene.animations) {
        samplers += animation.samplers.size();
    }
    std::uint64_t joints = 0;
    for (const scene::Skin& skin : scene.skins) {
        joints += skin.joints.size();
    }
    const std::uint64_t instances = scene.instances.size();
    const std::string ofNodes = " of " + std::to_string(nodes) + " nodes";
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, keyframeFloats * 4,
        "The animation keyframes (" + std::to_string(keyframeFloats) + " floats)"));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, samplers * sizeof(SamplerRecord),
        "The GPU animation records of " + std::to_string(samplers) + " samplers"));
    ENCORE_TRY(gpu::checkStorageBinding(limits, nodes * sizeof(NodeRecord),
                                        "The GPU animation records" + ofNodes));
    ENCORE_TRY(gpu::checkStorageBinding(limits, nodes * sizeof(glm::mat4),
                                        "The GPU-animated local and world matrices" + ofNodes));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, instances * sizeof(TransformUniform),
        "The GPU-animated transforms of " + std::to_string(instances) + " instances"));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, joints * sizeof(TransformRecord),
        "The GPU animation records of " + std::to_string(joints) + " joints"));
    const std::uint64_t largest = std::max({nodes, instances, joints});
    if (largest > kMaxWorkgroups * kWorkgroupSize) {
        return makeError(ErrorCode::LimitExceeded,
                         "GPU animation of " + std::to_string(largest) +
                             " nodes, instances or joints needs more workgroups in one dispatch "
                             "than WebGPU's maxComputeWorkgroupsPerDimension (" +
                             std::to_string(kMaxWorkgroups) + " of " +
                             std::to_string(kWorkgroupSize) + " threads).");
    }
    return {};
}

// Per animation: its clock, its time offset and its duration.
std::vector<AnimationRecord> animationRecords(const scene::SceneData& scene,
                                              std::span<const std::uint32_t> clockOf) {
    std::vector<AnimationRecord> records;
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        const scene::Animation& anim = scene.animations[a];
        const auto wrapped =
            float(scene::playbackTime(anim.timeOffset, anim.end, scene::PlaybackMode::Loop));
        // Rounding can carry a tiny negative offset up to `end` itself: that is 0 (and an
        // animation lasting 0 never wraps).
        const float wrappedOffset = anim.end > 0.0f && wrapped < anim.end ? wrapped : 0.0f;
        records.push_back({clockOf[a], anim.timeOffset, wrappedOffset, anim.end});
    }
    return records;
}

// Per node: 1 where some animation's channel drives it.
std::vector<std::uint8_t> animatedNodes(const scene::SceneData& scene) {
    std::vector<std::uint8_t> animated(scene.nodes.size(), 0);
    for (const scene::Animation& animation : scene.animations) {
        for (const scene::AnimationChannel& channel : animation.channels) {
            animated[channel.node.index()] = 1;
        }
    }
    return animated;
}

// Pass 1's records, one per animated node in node order: its rest pose and where its morph
// weights go. Their rest weights are appended to `keyframes`.
std::vector<NodeRecord> animatedNodeRecords(const scene::SceneData& scene,
                                            std::span<const std::uint8_t> animated,
                                            KeyframeStore& keyframes) {
    const std::vector<std::uint32_t> weightOffset = weightOffsets(scene);
    std::vector<NodeRecord> records;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (!animated[n]) {
            continue;
        }
        const scene::Node& node = scene.nodes[n];
        NodeRecord record{};
        record.restLocal = node.local;
        record.translation = glm::vec4(node.translation, 0.0f);
        record.rotation =
            glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w);
        record.scale = glm::vec4(node.scale, 0.0f);
        record.node = static_cast<std::uint32_t>(n);
        record.weightOffset = weightOffset[n];
        record.weightCount = static_cast<std::uint32_t>(node.weights.size());
        record.restWeights = keyframes.append(node.weights);
        records.push_back(record);
    }
    return records;
}

// Nodes at or below an animated node, grouped by depth (the loader guarantees a forest); also
// given as a flag per node (1: it moves).
std::vector<std::vector<WorldRecord>> movingNodesByDepth(const scene::SceneData& scene,
                                                         std::span<const std::uint8_t> animated,
                                                         std::vector<std::uint8_t>& moves) {
    const std::size_t nodeCount = scene.nodes.size();
    std::vector<std::vector<WorldRecord>> levels;
    moves.assign(nodeCount, 0);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;  // (node, depth)
    for (std::size_t root = 0; root < nodeCount; ++root) {
        if (scene.nodes[root].parent.valid()) {
            continue;
        }
        stack.emplace_back(static_cast<std::uint32_t>(root), 0u);
        while (!stack.empty()) {
            const auto [n, depth] = stack.back();
            stack.pop_back();
            const scene::Node& node = scene.nodes[n];
            moves[n] = animated[n] || (node.parent.valid() && moves[node.parent.index()]);
            if (moves[n]) {
                if (levels.size() <= depth) {
                    levels.resize(depth + 1);
                }
                levels[depth].push_back({n, node.parent.valid()
                                                ? static_cast<std::uint32_t>(node.parent.index())
                                                : kNone});
            }
            for (scene::NodeId child : node.children) {
                stack.emplace_back(static_cast<std::uint32_t>(child.index()), depth + 1);
            }
        }
    }
    return levels;
}

// Pass 2's records: the moving nodes level after level, parents first.
struct WorldLevels {
    std::vector<WorldRecord> records;
    std::vector<glm::uvec4> ranges;   // Per non-empty level: (first record, count, 0, 0).
    std::vector<std::uint8_t> moves;  // Per node: 1 at or below an animated node.
};

WorldLevels worldLevels(const scene::SceneData& scene, std::span<const std::uint8_t> animated) {
    WorldLevels world;
    for (const auto& level : movingNodesByDepth(scene, animated, world.moves)) {
        if (level.empty()) {
            continue;
        }
        world.ranges.emplace_back(world.records.size(), level.size(), 0, 0);
        world.records.insert(world.records.end(), level.begin(), level.end());
    }
    return world;
}

// Pass 3's instance records: the instances whose node moves, and which scene instances they are.
struct MovedInstances {
    std::vector<TransformRecord> records;
    std::vector<std::uint32_t> sceneInstances;
};

MovedInstances movedInstances(const scene::SceneData& scene,
                              std::span<const std::uint8_t> moves,
                              std::span<const std::uint32_t> slots) {
    MovedInstances moved;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& instance = scene.instances[i];
        if (!moves[instance.node.index()]) {
            continue;
        }
        TransformRecord record{};
        record.node = static_cast<std::uint32_t>(instance.node.index());
        record.slot = slots[i];
        record.transform = instance.instanceTransform;
        moved.records.push_back(record);
        moved.sceneInstances.push_back(static_cast<std::uint32_t>(i));
    }
    return moved;
}

// Pass 3's joint records: the joints whose node moves, each at its index among every skin's
// joints.
std::vector<TransformRecord> movedJoints(const scene::SceneData& scene,
                                         std::span<const std::uint8_t> moves) {
    std::vector<TransformRecord> records;
    std::uint32_t jointIndex = 0;
    for (const scene::Skin& skin : scene.skins) {
        for (std::size_t j = 0; j < skin.joints.size(); ++j, ++jointIndex) {
            if (!moves[skin.joints[j].index()]) {
                continue;
            }
            TransformRecord record{};
            record.node = static_cast<std::uint32_t>(skin.joints[j].index());
            record.slot = jointIndex;
            record.transform = skin.inverseBindMatrices[j];
            records.push_back(record);
        }
    }
    return records;
}

}  // namespace

Result<void> GpuAnimation::checkLimits(const gpu::DeviceLimits& limits,
                                       const scene::SceneData& scene) {
    return checkSizes(limits, scene,
                      layoutSamplers(scene).keyframes.size() + restWeightFloats(scene));
}

// The tables the passes read, built on the CPU from the scene alone.
struct GpuAnimation::Tables {
    // Every distinct run of sampler times and values, then the rest weights of animated nodes.
    KeyframeStore keyframes;
    std::vector<SamplerRecord> samplers;
    std::vector<AnimationRecord> animations;  // Their clock, offset and duration.
    std::vector<NodeRecord> nodes;            // Pass 1: one per animated node.
    WorldLevels world;                        // Pass 2.
    MovedInstances instances;                 // Pass 3.
    std::vector<TransformRecord> joints;      // Pass 3.
};

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
    SamplerLayout layout = layoutSamplers(scene);
    ENCORE_TRY(checkSizes(limits, scene, layout.keyframes.size() + restWeightFloats(scene)));
    auto result = std::unique_ptr<GpuAnimation>(new GpuAnimation());
    GpuAnimation& gpu = *result;
    gpu.mScene = &scene;
    gpu.mSamplerOffsets = std::move(layout.firstSampler);
    std::vector<std::uint32_t> clockOf;
    gpu.mClockEnds = animationClocks(scene, clockOf);

    Tables tables;
    tables.keyframes = std::move(layout.keyframes);
    tables.samplers = std::move(layout.samplers);
    tables.animations = animationRecords(scene, clockOf);
    const std::vector<std::uint8_t> animated = animatedNodes(scene);
    tables.nodes = animatedNodeRecords(scene, animated, tables.keyframes);
    tables.world = worldLevels(scene, animated);
    tables.instances = movedInstances(scene, tables.world.moves, instances.slots);
    if (animation) {  // Joint matrices go to AnimationBuffers' joint buffer: none without.
        tables.joints = movedJoints(scene, tables.world.moves);
    }
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

void GpuAnimation::keepIndices(const Tables& tables) {
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

void GpuAnimation::countStats(const Tables& tables) {
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
                                Tables& tables,
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
                                   const Tables& tables) {
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
                                  const Tables& tables,
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
