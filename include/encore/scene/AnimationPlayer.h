#pragma once

// AnimationPlayer evaluates a SceneData's animations on the CPU and keeps, ready for upload, the
// arrays a renderer needs to draw the animated scene:
//  - instanceWorlds() / instanceNormalMatrices(): one per SceneData::instances entry, in that
//    order, computed exactly as the loader computes Instance::world (node world times the
//    EXT_mesh_gpu_instancing transform);
//  - jointMatrices(): the joint matrices of every skin, skin after skin (skin s starts at
//    skinJointOffsets()[s]); jointMatrix = world(joint) * inverseBindMatrix, so a skinned vertex
//    comes out in world space. glTF says the transform of the skinned mesh's node is ignored:
//    a renderer draws skinned instances with these matrices *instead of* the instance's world
//    matrix (the Khronos sample renderer's inverse(world(meshNode)) * world(joint) * inverseBind
//    followed by world(meshNode) gives the same positions). jointNormalMatrices() holds the
//    inverse transpose of each, for normals and tangents;
//  - morphWeights(): the morph weights of every node whose mesh has morph targets, node after
//    node; instanceRanges()[i] says where instance i's joints and weights start;
//  - changedInstances() and changedSkins(): what the last evaluate() changed, so that only those
//    need uploading.
// glm::mat4 is column-major, 64 bytes, the layout of WGSL's mat4x4<f32> in a storage buffer.
//
// evaluate() does not allocate once the player is built and an animation selection made: key
// lookups use a cursor per sampler (O(1) when time moves forward), world matrices are recomputed
// only below nodes whose transform changed. The player reads the SceneData it was built from,
// which must outlive it and not change.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::scene {

enum class PlaybackMode : std::uint8_t {
    Clamp,  // Before an animation's first key: its first values; after its last: its last.
    Loop,   // Time wraps around each animation's own end time (t mod end; negative t wraps too).
};

// The time within an animation lasting `end` seconds at playback time `seconds`: `seconds`
// itself when clamped, wrapped into [0, end) when looping (an animation lasting 0 never wraps).
// The one rule for both evaluations: AnimationPlayer and render::GpuAnimation.
double playbackTime(double seconds, float end, PlaybackMode mode);

// Where one instance's data lies in the player's arrays (kNone: the instance has none).
struct InstanceAnimationRange {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    std::uint32_t jointOffset = kNone;  // Into jointMatrices(): the node's skin, if any.
    std::uint32_t jointCount = 0;
    std::uint32_t weightOffset = kNone;  // Into morphWeights(): the node's weights, if any.
    std::uint32_t weightCount = 0;
};

// What the last evaluate() did (for statistics: `encore stats`, benchmarks).
struct AnimationStats {
    std::uint32_t channelsEvaluated = 0;
    std::uint32_t nodesChanged = 0;      // Nodes whose local transform or weights changed.
    std::uint32_t worldsUpdated = 0;     // Node world matrices recomputed.
    std::uint32_t jointsUpdated = 0;     // Joint matrices recomputed.
    std::uint32_t instancesChanged = 0;  // == changedInstances().size().
};

// The animation `nameOrIndex` names: an exact name first, else a decimal index.
std::optional<AnimationId> findAnimation(const SceneData& scene, std::string_view nameOrIndex);

class AnimationPlayer {
  public:
    // Starts in the rest pose with every animation selected and PlaybackMode::Clamp.
    explicit AnimationPlayer(const SceneData& scene);

    // --- Which animations play (all by default). Changing the selection puts nodes that no
    // longer animate back to their rest pose at the next evaluate().
    void selectAll();
    void selectNone();
    Result<void> select(AnimationId animation);  // Only this one; an error if out of range.
    Result<void> select(std::string_view nameOrIndex);
    Result<void> select(std::span<const AnimationId> animations);
    std::span<const AnimationId> selection() const { return mSelection; }

    void setMode(PlaybackMode mode) { mMode = mode; }
    PlaybackMode mode() const { return mMode; }
    // The largest end time of the selected animations (0 with none).
    float duration() const;

    // Samples the selected animations at `seconds` and updates every output array. Channels of
    // different selected animations that drive the same property: the later animation wins.
    void evaluate(double seconds);

    // --- Results of the last evaluate() (before the first: the rest pose, as loaded).
    std::span<const glm::mat4> nodeLocals() const { return mLocal; }
    std::span<const glm::mat4> nodeWorlds() const { return mWorld; }
    std::span<const glm::mat4> instanceWorlds() const { return mInstanceWorld; }
    std::span<const glm::mat4> instanceNormalMatrices() const { return mInstanceNormal; }
    std::span<const InstanceAnimationRange> instanceRanges() const { return mInstanceRanges; }
    std::span<const glm::mat4> jointMatrices() const { return mJoints; }
    std::span<const glm::mat4> jointNormalMatrices() const { return mJointNormals; }
    std::span<const std::uint32_t> skinJointOffsets() const { return mSkinOffsets; }
    std::span<const float> morphWeights() const { return mWeights; }
    // Offset of a node's weights in morphWeights(), InstanceAnimationRange::kNone without.
    std::span<const std::uint32_t> nodeWeightOffsets() const { return mNodeWeightOffset; }

    // Instances whose world matrix or morph weights changed in the last evaluate() (indices into
    // SceneData::instances, ascending), and skins with a changed joint matrix. The first
    // evaluate() reports everything.
    std::span<const std::uint32_t> changedInstances() const { return mChangedInstances; }
    std::span<const std::uint32_t> changedSkins() const { return mChangedSkins; }
    const AnimationStats& stats() const { return mStats; }

    // Local TRS of node `node` after the last evaluate().
    glm::vec3 translation(NodeId node) const { return mTranslation[node.index()]; }
    glm::quat rotation(NodeId node) const { return mRotation[node.index()]; }
    glm::vec3 scale(NodeId node) const { return mScale[node.index()]; }

    const SceneData& scene() const { return *mScene; }

  private:
    struct ActiveChannel {
        const AnimationSampler* sampler;
        std::uint32_t animation;
        std::uint32_t cursor;  // Into mCursors.
        std::uint32_t node;
        AnimationPath path;
    };

    void rebuildChannels();
    // evaluate()'s steps: a node's pending pose back to its rest pose; the selected channels
    // sampled into the pending poses; a node's pending pose made current where it differs; the
    // world matrices of the nodes that moved; the instances whose matrices or weights changed.
    void resetToRest(std::uint32_t node);
    void sampleChannels();
    void commitPose(std::uint32_t node);
    void updateWorlds();
    void collectChangedInstances();
    void updateSkins(bool all);

    const SceneData* mScene;
    std::vector<AnimationId> mSelection;
    PlaybackMode mMode = PlaybackMode::Clamp;
    bool mFirst = true;

    std::vector<ActiveChannel> mChannels;
    std::vector<SamplerCursor> mCursors;        // One per sampler of every animation.
    std::vector<std::uint32_t> mCursorOffsets;  // First cursor of each animation.
    std::vector<std::uint32_t> mAnimatedNodes;  // Nodes the selection drives (ascending).
    std::vector<std::uint32_t> mRestoreNodes;   // Nodes to put back to rest next time.
    std::vector<float> mAnimationTimes;         // Per animation, this evaluate's local time.

    std::vector<std::uint32_t> mOrder;  // Parents before children.
    std::vector<glm::vec3> mTranslation, mPendingTranslation;
    std::vector<glm::quat> mRotation, mPendingRotation;
    std::vector<glm::vec3> mScale, mPendingScale;
    std::vector<glm::mat4> mLocal, mWorld;
    std::vector<std::uint8_t> mLocalChanged, mWorldChanged, mWeightsChanged;

    std::vector<float> mWeights, mPendingWeights, mRestWeights;
    std::vector<std::uint32_t> mNodeWeightOffset;

    std::vector<glm::mat4> mInstanceWorld, mInstanceNormal;
    std::vector<InstanceAnimationRange> mInstanceRanges;
    std::vector<glm::mat4> mJoints, mJointNormals;
    std::vector<std::uint32_t> mSkinOffsets;

    std::vector<std::uint32_t> mChangedInstances, mChangedSkins;
    AnimationStats mStats;
};

}  // namespace encore::scene
