#include "render/animation/AnimationTables.h"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "encore/scene/AnimationPlayer.h"
#include "gpu/Upload.h"
#include "render/BindGroupLayouts.h"

namespace encore::render {

namespace {

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

// The offset of each node's weights in AnimationPlayer::morphWeights() (kNoAnimationIndex without).
std::vector<std::uint32_t> weightOffsets(const scene::SceneData& scene) {
    std::vector<std::uint32_t> offsets(scene.nodes.size(), kNoAnimationIndex);
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

// checkAnimationTables, given the keyframe floats that the scene stores once shared.
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
    if (largest > kMaxAnimationWorkgroups * kAnimationWorkgroupSize) {
        return makeError(ErrorCode::LimitExceeded,
                         "GPU animation of " + std::to_string(largest) +
                             " nodes, instances or joints needs more workgroups in one dispatch "
                             "than WebGPU's maxComputeWorkgroupsPerDimension (" +
                             std::to_string(kMaxAnimationWorkgroups) + " of " +
                             std::to_string(kAnimationWorkgroupSize) + " threads).");
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
                                                : kNoAnimationIndex});
            }
            for (scene::NodeId child : node.children) {
                stack.emplace_back(static_cast<std::uint32_t>(child.index()), depth + 1);
            }
        }
    }
    return levels;
}

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

Result<void> checkAnimationTables(const gpu::DeviceLimits& limits, const scene::SceneData& scene) {
    return checkSizes(limits, scene,
                      layoutSamplers(scene).keyframes.size() + restWeightFloats(scene));
}

Result<AnimationTables> buildAnimationTables(const gpu::DeviceLimits& limits,
                                             const scene::SceneData& scene,
                                             std::span<const std::uint32_t> instanceSlots,
                                             bool joints) {
    SamplerLayout layout = layoutSamplers(scene);
    ENCORE_TRY(checkSizes(limits, scene, layout.keyframes.size() + restWeightFloats(scene)));
    AnimationTables tables;
    std::vector<std::uint32_t> clockOf;
    tables.clockEnds = animationClocks(scene, clockOf);
    tables.keyframes = std::move(layout.keyframes);
    tables.samplers = std::move(layout.samplers);
    tables.firstSampler = std::move(layout.firstSampler);
    tables.animations = animationRecords(scene, clockOf);
    const std::vector<std::uint8_t> animated = animatedNodes(scene);
    tables.nodes = animatedNodeRecords(scene, animated, tables.keyframes);
    tables.world = worldLevels(scene, animated);
    tables.instances = movedInstances(scene, tables.world.moves, instanceSlots);
    if (joints) {
        tables.joints = movedJoints(scene, tables.world.moves);
    }
    return tables;
}

}  // namespace encore::render
