#include "render/AnimationBuffers.h"

#include <algorithm>
#include <cstring>

#include "gpu/BindingResource.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/InstanceBuffer.h"
#include "render/RenderEncoder.h"
#include "render/ShadingSemantics.h"

namespace encore::render {

namespace {

constexpr std::uint8_t kSkinned = 1;
constexpr std::uint8_t kMorphed = 2;
constexpr std::uint8_t kEightJoints = 4;
constexpr std::uint32_t kNone = scene::InstanceAnimationRange::kNone;
// minUniformBufferOffsetAlignment: each draw record starts on its own 256 bytes.
constexpr std::uint32_t kDrawStride = 256;

struct DrawRecord {
    std::uint32_t deltaOffset = 0;
    std::uint32_t vertexCount = 0;
    std::uint32_t targetCount = 0;
    std::uint32_t jointOffset = kNone;
    std::uint32_t weightOffset = kNone;
};

void packJoints(std::span<const glm::mat4> joints,
                std::span<const glm::mat4> normals,
                std::size_t first,
                std::size_t count,
                std::vector<TransformUniform>& out) {
    for (std::size_t j = first; j < first + count; ++j) {
        std::memcpy(out[j].world, &joints[j][0][0], sizeof(out[j].world));
        std::memcpy(out[j].normal, &normals[j][0][0], sizeof(out[j].normal));
    }
}

// [mesh][primitive]: kSkinned, kMorphed, kEightJoints. Meshes drawn by a node with a skin get
// the SKINNED variant where they have joints.
std::vector<std::vector<std::uint8_t>> primitiveFlags(const scene::SceneData& scene) {
    std::vector<std::uint8_t> meshSkinned(scene.meshes.size(), 0);
    for (const scene::Instance& instance : scene.instances) {
        if (scene.nodes[instance.node.index()].skin.has_value()) {
            meshSkinned[instance.mesh.index()] = 1;
        }
    }
    std::vector<std::vector<std::uint8_t>> flags(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const auto& primitives = scene.meshes[m].primitives;
        flags[m].assign(primitives.size(), 0);
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const scene::Primitive& primitive = primitives[p];
            if (meshSkinned[m] && primitive.attribute(scene::Semantic::Joints0) &&
                primitive.attribute(scene::Semantic::Weights0)) {
                flags[m][p] |= kSkinned;
                if (primitive.attribute(scene::Semantic::Joints1) &&
                    primitive.attribute(scene::Semantic::Weights1)) {
                    flags[m][p] |= kEightJoints;
                }
            }
            if (!primitive.targets.empty()) {
                flags[m][p] |= kMorphed;
            }
        }
    }
    return flags;
}

std::uint32_t countPrimitives(const std::vector<std::vector<std::uint8_t>>& flags,
                              std::uint8_t flag) {
    std::uint32_t count = 0;
    for (const std::vector<std::uint8_t>& meshFlags : flags) {
        count += static_cast<std::uint32_t>(
            std::count_if(meshFlags.begin(), meshFlags.end(),
                          [flag](std::uint8_t primitive) { return (primitive & flag) != 0; }));
    }
    return count;
}

// Morph deltas, primitive after primitive: target-major, then vertex, then attribute.
struct MorphDeltas {
    std::vector<glm::vec4> deltas;
    std::vector<std::vector<std::uint32_t>> offsets;  // [mesh][primitive]; 0 without targets.
};

void appendMorphDeltas(const scene::SceneData& scene,
                       const scene::Primitive& primitive,
                       std::vector<glm::vec4>& deltas) {
    const std::size_t vertices = primitive.vertexCount;
    const std::size_t base = deltas.size();
    deltas.resize(base + primitive.targets.size() * vertices * 3, glm::vec4(0.0f));
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
        const scene::MorphTarget& target = primitive.targets[t];
        const std::optional<scene::AccessorId> attributes[3] = {target.position, target.normal,
                                                                target.tangent};
        for (int a = 0; a < 3; ++a) {
            if (!attributes[a]) {
                continue;
            }
            const std::vector<glm::vec4> values = scene.readFloats(*attributes[a]);
            const std::size_t count = std::min(values.size(), vertices);
            for (std::size_t v = 0; v < count; ++v) {
                deltas[base + (t * vertices + v) * 3 + a] = glm::vec4(glm::vec3(values[v]), 0.0f);
            }
        }
    }
}

MorphDeltas morphDeltas(const scene::SceneData& scene) {
    MorphDeltas morph;
    morph.offsets.resize(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const auto& primitives = scene.meshes[m].primitives;
        morph.offsets[m].assign(primitives.size(), 0);
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            if (!primitives[p].targets.empty()) {
                morph.offsets[m][p] = static_cast<std::uint32_t>(morph.deltas.size());
                appendMorphDeltas(scene, primitives[p], morph.deltas);
            }
        }
    }
    return morph;
}

// Draw records: every primitive of every instance whose mesh has an animated primitive, each
// kDrawStride bytes. `firstDraw` gets each scene instance's first record (kNone without).
std::vector<std::uint8_t> drawRecords(const scene::SceneData& scene,
                                      const std::vector<std::vector<std::uint8_t>>& primitiveFlags,
                                      const std::vector<std::vector<std::uint32_t>>& deltaOffsets,
                                      std::span<const scene::InstanceAnimationRange> ranges,
                                      std::vector<std::uint32_t>& firstDraw) {
    std::vector<std::uint8_t> records;
    firstDraw.assign(scene.instances.size(), kNone);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const std::size_t m = scene.instances[i].mesh.index();
        const auto& flags = primitiveFlags[m];
        if (std::all_of(flags.begin(), flags.end(), [](std::uint8_t f) { return f == 0; })) {
            continue;
        }
        firstDraw[i] = static_cast<std::uint32_t>(records.size() / kDrawStride);
        for (std::size_t p = 0; p < flags.size(); ++p) {
            const scene::Primitive& primitive = scene.meshes[m].primitives[p];
            DrawRecord record;
            record.deltaOffset = deltaOffsets[m][p];
            record.vertexCount = primitive.vertexCount;
            record.targetCount = static_cast<std::uint32_t>(primitive.targets.size());
            record.jointOffset = (flags[p] & kSkinned) ? ranges[i].jointOffset : kNone;
            record.weightOffset = (flags[p] & kMorphed) ? ranges[i].weightOffset : kNone;
            const std::size_t at = records.size();
            records.resize(at + kDrawStride, 0);
            std::memcpy(records.data() + at, &record, sizeof(record));
        }
    }
    if (records.empty()) {
        records.resize(kDrawStride, 0);  // No instance draws an animated mesh; bind something.
    }
    return records;
}

// Per instance slot (InstanceBuffer order): the joint and weight offsets of the scene instance
// there (kNone where it has none).
std::vector<glm::uvec2> offsetsBySlot(const scene::SceneData& scene,
                                      std::span<const glm::uvec2> instanceRanges) {
    const std::vector<std::uint32_t> slots = instanceSlots(scene);
    std::vector<glm::uvec2> offsets(scene.instances.size(), glm::uvec2(kNone));
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        offsets[slots[i]] = instanceRanges[i];
    }
    return offsets;
}

// Where the buffers come from: mapped at creation, or written into a kept buffer when a pool
// gives one.
struct BufferSource {
    const wgpu::Device& device;
    const wgpu::Queue& queue;
    gpu::ResourcePool* pool;

    wgpu::Buffer upload(wgpu::BufferUsage usage,
                        std::span<const std::uint8_t> bytes,
                        const char* label) const {
        return gpu::bufferWithData(pool, device, queue, usage, bytes, label);
    }

    // A storage buffer of `values`; one zeroed element when there are none (as
    // gpu::createStorageBuffer: WebGPU binds no empty buffer).
    template <typename T>
    wgpu::Buffer storage(std::span<const T> values,
                         wgpu::BufferUsage extra,
                         const char* label) const {
        const T zero{};
        const std::span<const T> bound = values.empty() ? std::span<const T>(&zero, 1) : values;
        return upload(wgpu::BufferUsage::Storage | extra,
                      {reinterpret_cast<const std::uint8_t*>(bound.data()), bound.size_bytes()},
                      label);
    }
};

}  // namespace

std::vector<scene::Semantic> unlitPrimitiveSemantics(const AnimationBuffers* animation,
                                                     scene::MeshId mesh,
                                                     std::size_t primitive,
                                                     shaders::ShaderVariantKey& variant) {
    std::vector<scene::Semantic> semantics(kUnlitTransformSemantics.begin(),
                                           kUnlitTransformSemantics.end());
    if (animation) {
        animation->addVariantFlags(mesh, primitive, variant);
        appendAnimationSemantics(variant, semantics);
    }
    return semantics;
}

void appendAnimationSemantics(const shaders::ShaderVariantKey& key,
                              std::vector<scene::Semantic>& semantics) {
    if (key.skinned) {
        semantics.push_back(scene::Semantic::Joints0);
        semantics.push_back(scene::Semantic::Weights0);
        if (key.skinned8) {
            semantics.push_back(scene::Semantic::Joints1);
            semantics.push_back(scene::Semantic::Weights1);
        }
    }
}

void AnimationBuffers::giveBackTo(gpu::ResourcePool& pool) {
    mBindGroup = nullptr;
    for (wgpu::Buffer* buffer : {&mDraws, &mJoints, &mWeights, &mDeltas, &mInstanceOffsets}) {
        pool.giveBack(std::move(*buffer));
    }
}

std::unique_ptr<AnimationBuffers> AnimationBuffers::create(const wgpu::Device& device,
                                                           const wgpu::Queue& queue,
                                                           const BindGroupLayouts& layouts,
                                                           const scene::SceneData& scene,
                                                           const scene::AnimationPlayer& player,
                                                           gpu::ResourcePool* pool) {
    auto result = std::unique_ptr<AnimationBuffers>(new AnimationBuffers());
    AnimationBuffers& buffers = *result;
    buffers.mPrimitiveFlags = primitiveFlags(scene);
    buffers.mSkinnedPrimitives = countPrimitives(buffers.mPrimitiveFlags, kSkinned);
    buffers.mMorphedPrimitives = countPrimitives(buffers.mPrimitiveFlags, kMorphed);
    if (buffers.mSkinnedPrimitives == 0 && buffers.mMorphedPrimitives == 0) {
        return nullptr;
    }
    const MorphDeltas morph = morphDeltas(scene);
    const auto ranges = player.instanceRanges();
    const BufferSource source{device, queue, pool};
    const std::vector<std::uint8_t> records =
        drawRecords(scene, buffers.mPrimitiveFlags, morph.offsets, ranges, buffers.mFirstDraw);
    buffers.mDraws = source.upload(wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst, records,
                                   "animation draws");

    buffers.mInstanceRanges.resize(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        buffers.mInstanceRanges[i] = glm::uvec2(ranges[i].jointOffset, ranges[i].weightOffset);
    }
    const std::vector<glm::uvec2> offsets = offsetsBySlot(scene, buffers.mInstanceRanges);
    constexpr wgpu::BufferUsage kWritable = wgpu::BufferUsage::CopyDst;
    buffers.mInstanceOffsets =
        source.storage(std::span<const glm::uvec2>(offsets), kWritable, "instance animation");

    const auto joints = player.jointMatrices();
    buffers.mJointScratch.resize(joints.size());
    packJoints(joints, player.jointNormalMatrices(), 0, joints.size(), buffers.mJointScratch);
    buffers.mJoints = source.storage(std::span<const TransformUniform>(buffers.mJointScratch),
                                     kWritable | wgpu::BufferUsage::CopySrc, "joint matrices");
    const auto weights = player.morphWeights();
    buffers.mWeights = source.storage(std::span<const float>(weights.data(), weights.size()),
                                      kWritable | wgpu::BufferUsage::CopySrc, "morph weights");
    buffers.mDeltas =
        source.storage(std::span<const glm::vec4>(morph.deltas), kWritable, "morph deltas");

    buffers.mBindGroup =
        gpu::makeBindGroup(device, layouts.animation,
                           {{0, buffers.mDraws, 0, sizeof(DrawRecord)},
                            {1, buffers.mJoints, 0, buffers.mJoints.GetSize()},
                            {2, buffers.mWeights, 0, buffers.mWeights.GetSize()},
                            {3, buffers.mDeltas, 0, buffers.mDeltas.GetSize()},
                            {4, buffers.mInstanceOffsets, 0, buffers.mInstanceOffsets.GetSize()}},
                           "animation");
    return result;
}

void AnimationBuffers::addVariantFlags(scene::MeshId mesh,
                                       std::size_t primitive,
                                       shaders::ShaderVariantKey& key) const {
    const std::uint8_t flags = mPrimitiveFlags[mesh.index()][primitive];
    key.skinned = (flags & kSkinned) != 0;
    key.skinned8 = key.skinned && (flags & kEightJoints) != 0;
    key.morphed = (flags & kMorphed) != 0;
}

std::uint32_t AnimationBuffers::drawOffset(std::size_t sceneInstance, std::size_t primitive) const {
    const std::uint32_t first = mFirstDraw[sceneInstance];
    return first == kNone ? 0 : (first + static_cast<std::uint32_t>(primitive)) * kDrawStride;
}

bool AnimationBuffers::skinnedPrimitive(scene::MeshId mesh, std::size_t primitive) const {
    return (mPrimitiveFlags[mesh.index()][primitive] & kSkinned) != 0;
}

void AnimationBuffers::bind(RenderEncoder& encoder,
                            const shaders::ShaderVariantKey& key,
                            std::size_t sceneInstance,
                            std::size_t primitive) const {
    if (!key.animated()) {
        return;
    }
    encoder.setBindGroup(animationGroupIndex(key), mBindGroup,
                         drawOffset(sceneInstance, primitive));
}

AnimationUploadStats AnimationBuffers::write(const wgpu::Queue& queue,
                                             const scene::AnimationPlayer& player) {
    AnimationUploadStats stats;
    const auto joints = player.jointMatrices();
    const auto skinOffsets = player.skinJointOffsets();
    for (std::uint32_t skin : player.changedSkins()) {
        const std::size_t first = skinOffsets[skin];
        const std::size_t end =
            skin + 1 < skinOffsets.size() ? skinOffsets[skin + 1] : joints.size();
        if (end <= first) {
            continue;
        }
        packJoints(joints, player.jointNormalMatrices(), first, end - first, mJointScratch);
        const std::uint64_t bytes = (end - first) * sizeof(TransformUniform);
        queue.WriteBuffer(mJoints, first * sizeof(TransformUniform), &mJointScratch[first], bytes);
        stats.jointsWritten += static_cast<std::uint32_t>(end - first);
        stats.bytesWritten += bytes;
    }
    const auto weights = player.morphWeights();
    if (!weights.empty() && !player.changedInstances().empty()) {
        queue.WriteBuffer(mWeights, 0, weights.data(), weights.size_bytes());
        stats.weightsWritten = static_cast<std::uint32_t>(weights.size());
        stats.bytesWritten += weights.size_bytes();
    }
    return stats;
}

}  // namespace encore::render
