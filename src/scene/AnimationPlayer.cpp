// The CPU animation player. Every array is sized when the player is built or the selection
// changes; evaluate() only overwrites. Each evaluation starts the driven nodes from their rest
// pose, applies the channels into "pending" TRS and weights, and compares them with the current
// ones, so that a clamped animation past its end, or a property that does not move, costs no
// matrix work and reports no change.

#include "encore/scene/AnimationPlayer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace encore::scene {

std::optional<AnimationId> findAnimation(const SceneData& scene, std::string_view nameOrIndex) {
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        if (scene.animations[a].name == nameOrIndex) {
            return AnimationId(a);
        }
    }
    std::size_t index = 0;
    const char* end = nameOrIndex.data() + nameOrIndex.size();
    const auto [next, error] = std::from_chars(nameOrIndex.data(), end, index);
    if (error == std::errc() && next == end && !nameOrIndex.empty() &&
        index < scene.animations.size()) {
        return AnimationId(index);
    }
    return std::nullopt;
}

AnimationPlayer::AnimationPlayer(const SceneData& scene) : mScene(&scene) {
    const std::size_t nodes = scene.nodes.size();
    mTranslation.resize(nodes);
    mRotation.resize(nodes);
    mScale.resize(nodes);
    mLocal.resize(nodes);
    mWorld.resize(nodes);
    mNodeWeightOffset.assign(nodes, InstanceAnimationRange::kNone);
    for (std::size_t n = 0; n < nodes; ++n) {
        const Node& node = scene.nodes[n];
        mTranslation[n] = node.translation;
        mRotation[n] = node.rotation;
        mScale[n] = node.scale;
        mLocal[n] = node.local;
        mWorld[n] = node.world;
        if (!node.weights.empty()) {
            mNodeWeightOffset[n] = static_cast<std::uint32_t>(mRestWeights.size());
            mRestWeights.insert(mRestWeights.end(), node.weights.begin(), node.weights.end());
        }
    }
    mPendingTranslation = mTranslation;
    mPendingRotation = mRotation;
    mPendingScale = mScale;
    mWeights = mRestWeights;
    mPendingWeights = mRestWeights;
    mLocalChanged.assign(nodes, 0);
    mWorldChanged.assign(nodes, 0);
    mWeightsChanged.assign(nodes, 0);

    // The loader guarantees a forest: a depth-first walk from the roots orders parents first.
    mOrder.reserve(nodes);
    std::vector<std::uint32_t> stack;
    for (std::size_t root = 0; root < nodes; ++root) {
        if (scene.nodes[root].parent.valid()) {
            continue;
        }
        stack.push_back(static_cast<std::uint32_t>(root));
        while (!stack.empty()) {
            const std::uint32_t index = stack.back();
            stack.pop_back();
            mOrder.push_back(index);
            for (NodeId child : scene.nodes[index].children) {
                stack.push_back(static_cast<std::uint32_t>(child.index()));
            }
        }
    }

    for (const Skin& skin : scene.skins) {
        mSkinOffsets.push_back(static_cast<std::uint32_t>(mJoints.size()));
        mJoints.resize(mJoints.size() + skin.joints.size());
    }
    mJointNormals.resize(mJoints.size());
    updateSkins(true);
    mChangedSkins.clear();
    mStats = {};

    mInstanceWorld.reserve(scene.instances.size());
    for (const Instance& instance : scene.instances) {
        mInstanceWorld.push_back(instance.world);
        mInstanceNormal.push_back(instance.normalMatrix);
        const Node& node = scene.nodes[instance.node.index()];
        InstanceAnimationRange range;
        if (node.skin) {
            range.jointOffset = mSkinOffsets[node.skin->index()];
            range.jointCount =
                static_cast<std::uint32_t>(scene.skins[node.skin->index()].joints.size());
        }
        if (!node.weights.empty()) {
            range.weightOffset = mNodeWeightOffset[instance.node.index()];
            range.weightCount = static_cast<std::uint32_t>(node.weights.size());
        }
        mInstanceRanges.push_back(range);
    }
    mChangedInstances.reserve(scene.instances.size());
    mChangedSkins.reserve(scene.skins.size());

    mCursorOffsets.reserve(scene.animations.size());
    std::size_t cursors = 0;
    for (const Animation& animation : scene.animations) {
        mCursorOffsets.push_back(static_cast<std::uint32_t>(cursors));
        cursors += animation.samplers.size();
    }
    mCursors.resize(cursors);
    mAnimationTimes.resize(scene.animations.size());
    selectAll();
}

void AnimationPlayer::selectAll() {
    mSelection.clear();
    for (std::size_t a = 0; a < mScene->animations.size(); ++a) {
        mSelection.push_back(AnimationId(a));
    }
    rebuildChannels();
}

void AnimationPlayer::selectNone() {
    mSelection.clear();
    rebuildChannels();
}

Result<void> AnimationPlayer::select(AnimationId animation) {
    return select(std::span<const AnimationId>(&animation, 1));
}

Result<void> AnimationPlayer::select(std::string_view nameOrIndex) {
    const auto found = findAnimation(*mScene, nameOrIndex);
    if (!found) {
        return makeError(ErrorCode::InvalidArgument,
                         "The asset has no animation named or numbered '" +
                             std::string(nameOrIndex) + "' (it has " +
                             std::to_string(mScene->animations.size()) + " animations).");
    }
    return select(*found);
}

Result<void> AnimationPlayer::select(std::span<const AnimationId> animations) {
    for (const AnimationId animation : animations) {
        if (!animation.valid() || animation.index() >= mScene->animations.size()) {
            return makeError(ErrorCode::InvalidArgument,
                             "Animation " + std::to_string(animation.value) +
                                 " does not exist (the asset has " +
                                 std::to_string(mScene->animations.size()) + " animations).");
        }
    }
    mSelection.assign(animations.begin(), animations.end());
    rebuildChannels();
    return {};
}

float AnimationPlayer::duration() const {
    float end = 0.0f;
    for (const AnimationId animation : mSelection) {
        end = std::max(end, mScene->animations[animation.index()].end);
    }
    return end;
}

void AnimationPlayer::rebuildChannels() {
    // Nodes driven until now go back to rest unless the new selection drives them too; the
    // restore happens in the next evaluate() so that its change detection reports it.
    mRestoreNodes.insert(mRestoreNodes.end(), mAnimatedNodes.begin(), mAnimatedNodes.end());
    mChannels.clear();
    mAnimatedNodes.clear();
    for (const AnimationId id : mSelection) {
        const Animation& animation = mScene->animations[id.index()];
        for (const AnimationChannel& channel : animation.channels) {
            mChannels.push_back(ActiveChannel{
                &animation.samplers[channel.sampler], static_cast<std::uint32_t>(id.index()),
                mCursorOffsets[id.index()] + channel.sampler,
                static_cast<std::uint32_t>(channel.node.index()), channel.path});
            mAnimatedNodes.push_back(static_cast<std::uint32_t>(channel.node.index()));
        }
    }
    for (auto* list : {&mAnimatedNodes, &mRestoreNodes}) {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    // Reserve now so that evaluate() never grows these.
    mRestoreNodes.reserve(mRestoreNodes.size() + mAnimatedNodes.size());
}

double playbackTime(double seconds, float end, PlaybackMode mode) {
    if (mode != PlaybackMode::Loop || !(end > 0.0f)) {
        return seconds;
    }
    double time = std::fmod(seconds, double(end));
    if (time < 0.0) {
        time += end;
    }
    return time;
}

void AnimationPlayer::evaluate(double seconds) {
    const SceneData& scene = *mScene;
    mStats = {};
    mChangedInstances.clear();
    mChangedSkins.clear();
    for (const AnimationId id : mSelection) {
        const Animation& animation = scene.animations[id.index()];
        mAnimationTimes[id.index()] = static_cast<float>(
            playbackTime(seconds + double(animation.timeOffset), animation.end, mMode));
    }
    // Start from the rest pose: nodes the selection drives, and nodes it stopped driving.
    for (const std::uint32_t n : mRestoreNodes) {
        resetToRest(n);
    }
    for (const std::uint32_t n : mAnimatedNodes) {
        resetToRest(n);
    }
    sampleChannels();
    for (const std::uint32_t n : mRestoreNodes) {
        commitPose(n);
    }
    for (const std::uint32_t n : mAnimatedNodes) {
        commitPose(n);
    }
    mRestoreNodes.clear();
    updateWorlds();
    collectChangedInstances();
    updateSkins(mFirst);
    for (const std::uint32_t n : mOrder) {
        mLocalChanged[n] = 0;
        mWorldChanged[n] = 0;
        mWeightsChanged[n] = 0;
    }
    mFirst = false;
}

void AnimationPlayer::resetToRest(std::uint32_t n) {
    const Node& node = mScene->nodes[n];
    mPendingTranslation[n] = node.translation;
    mPendingRotation[n] = node.rotation;
    mPendingScale[n] = node.scale;
    if (const std::uint32_t offset = mNodeWeightOffset[n];
        offset != InstanceAnimationRange::kNone) {
        std::copy_n(mRestWeights.begin() + offset, node.weights.size(),
                    mPendingWeights.begin() + offset);
    }
}

void AnimationPlayer::sampleChannels() {
    for (ActiveChannel& channel : mChannels) {
        const float time = mAnimationTimes[channel.animation];
        SamplerCursor& cursor = mCursors[channel.cursor];
        const std::uint32_t n = channel.node;
        switch (channel.path) {
            case AnimationPath::Translation:
                sampleAnimation(*channel.sampler, time, false, cursor,
                                std::span<float>(&mPendingTranslation[n].x, 3));
                break;
            case AnimationPath::Scale:
                sampleAnimation(*channel.sampler, time, false, cursor,
                                std::span<float>(&mPendingScale[n].x, 3));
                break;
            case AnimationPath::Rotation: {
                float q[4];  // glTF order: x, y, z, w.
                sampleAnimation(*channel.sampler, time, true, cursor, q);
                mPendingRotation[n] = glm::quat(q[3], q[0], q[1], q[2]);
                break;
            }
            case AnimationPath::Weights:
                sampleAnimation(
                    *channel.sampler, time, false, cursor,
                    std::span<float>(mPendingWeights)
                        .subspan(mNodeWeightOffset[n], mScene->nodes[n].weights.size()));
                break;
        }
        ++mStats.channelsEvaluated;
    }
}

// Compares with the current pose: only real changes move matrices.
void AnimationPlayer::commitPose(std::uint32_t n) {
    if (mPendingTranslation[n] != mTranslation[n] || mPendingRotation[n] != mRotation[n] ||
        mPendingScale[n] != mScale[n]) {
        mTranslation[n] = mPendingTranslation[n];
        mRotation[n] = mPendingRotation[n];
        mScale[n] = mPendingScale[n];
        if (!mLocalChanged[n]) {
            mLocalChanged[n] = 1;
            ++mStats.nodesChanged;
        }
    }
    if (const std::uint32_t offset = mNodeWeightOffset[n];
        offset != InstanceAnimationRange::kNone) {
        const std::size_t count = mScene->nodes[n].weights.size();
        if (!std::equal(mPendingWeights.begin() + offset, mPendingWeights.begin() + offset + count,
                        mWeights.begin() + offset)) {
            std::copy_n(mPendingWeights.begin() + offset, count, mWeights.begin() + offset);
            mWeightsChanged[n] = 1;
            if (!mLocalChanged[n]) {
                ++mStats.nodesChanged;
            }
        }
    }
}

// World matrices, parents first; a node whose parent moved moves too.
void AnimationPlayer::updateWorlds() {
    for (const std::uint32_t n : mOrder) {
        const Node& node = mScene->nodes[n];
        const bool parentChanged = node.parent.valid() && mWorldChanged[node.parent.index()];
        if (!mLocalChanged[n] && !parentChanged && !mFirst) {
            continue;
        }
        if (mLocalChanged[n]) {
            // A node back at its exact rest pose gets the loader's matrix (bit-identical).
            const bool atRest = mTranslation[n] == node.translation &&
                                mRotation[n] == node.rotation && mScale[n] == node.scale;
            mLocal[n] = atRest ? node.local : composeTrs(mTranslation[n], mRotation[n], mScale[n]);
        }
        mWorld[n] = node.parent.valid() ? mWorld[node.parent.index()] * mLocal[n] : mLocal[n];
        mWorldChanged[n] = 1;
        ++mStats.worldsUpdated;
    }
}

void AnimationPlayer::collectChangedInstances() {
    const SceneData& scene = *mScene;
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const std::size_t n = instance.node.index();
        const bool moved = mWorldChanged[n] != 0;
        if (moved) {
            mInstanceWorld[i] = mWorld[n] * instance.instanceTransform;
            mInstanceNormal[i] = normalMatrixOf(mInstanceWorld[i]);
        }
        if (moved || mWeightsChanged[n] || mFirst) {
            mChangedInstances.push_back(static_cast<std::uint32_t>(i));
        }
    }
    mStats.instancesChanged = static_cast<std::uint32_t>(mChangedInstances.size());
}

void AnimationPlayer::updateSkins(bool all) {
    const SceneData& scene = *mScene;
    for (std::size_t s = 0; s < scene.skins.size(); ++s) {
        const Skin& skin = scene.skins[s];
        bool changed = all;
        for (std::size_t j = 0; j < skin.joints.size() && !changed; ++j) {
            changed = mWorldChanged[skin.joints[j].index()] != 0;
        }
        if (!changed) {
            continue;
        }
        const std::uint32_t offset = mSkinOffsets[s];
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            const glm::mat4 joint = mWorld[skin.joints[j].index()] * skin.inverseBindMatrices[j];
            mJoints[offset + j] = joint;
            mJointNormals[offset + j] = normalMatrixOf(joint);
        }
        mStats.jointsUpdated += static_cast<std::uint32_t>(skin.joints.size());
        mChangedSkins.push_back(static_cast<std::uint32_t>(s));
    }
}

}  // namespace encore::scene
