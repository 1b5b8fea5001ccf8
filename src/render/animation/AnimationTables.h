#pragma once

// The tables GPU animation's compute passes read (animation_sample.wgsl, animation_world.wgsl,
// animation_transforms.wgsl), built on the CPU from the SceneData alone, in the same orders
// AnimationPlayer uses (node weights node after node, joints skin after skin), so that the passes
// write where the CPU path writes. GpuAnimation uploads and binds them.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/scene/SceneData.h"
#include "render/animation/KeyframeStore.h"

namespace encore::render {

constexpr std::uint32_t kNoAnimationIndex = 0xFFFFFFFFu;  // No node, no weights.
constexpr std::uint32_t kAnimationWorkgroupSize = 64;     // kWorkgroupSize of animation_*.wgsl.
constexpr std::uint64_t kMaxAnimationWorkgroups = 65535;  // maxComputeWorkgroupsPerDimension.

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

// Pass 2's records: the moving nodes level after level, parents first.
struct WorldLevels {
    std::vector<WorldRecord> records;
    std::vector<glm::uvec4> ranges;   // Per non-empty level: (first record, count, 0, 0).
    std::vector<std::uint8_t> moves;  // Per node: 1 at or below an animated node.
};

// Pass 3's instance records: the instances whose node moves, and which scene instances they are.
struct MovedInstances {
    std::vector<TransformRecord> records;
    std::vector<std::uint32_t> sceneInstances;
};

struct AnimationTables {
    // Every distinct run of sampler times and values, then the rest weights of animated nodes.
    KeyframeStore keyframes;
    std::vector<SamplerRecord> samplers;
    std::vector<std::uint32_t> firstSampler;  // Per animation: its first record in `samplers`.
    std::vector<AnimationRecord> animations;  // Their clock, offset and duration.
    std::vector<float> clockEnds;   // Per clock: the duration of the animations that share it.
    std::vector<NodeRecord> nodes;  // Pass 1: one per animated node.
    WorldLevels world;              // Pass 2.
    MovedInstances instances;       // Pass 3.
    std::vector<TransformRecord> joints;  // Pass 3; none unless asked for.
};

// Whether the tables of `scene` fit the device's storage bindings and dispatch sizes.
Result<void> checkAnimationTables(const gpu::DeviceLimits& limits, const scene::SceneData& scene);

// The tables of `scene`, whose instances the passes write at `instanceSlots` (one per scene
// instance); with `joints`, the joint records too. Fails as checkAnimationTables does.
Result<AnimationTables> buildAnimationTables(const gpu::DeviceLimits& limits,
                                             const scene::SceneData& scene,
                                             std::span<const std::uint32_t> instanceSlots,
                                             bool joints);

}  // namespace encore::render
