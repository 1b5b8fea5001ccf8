#pragma once

// The scene's animation data on the GPU, shared by every strategy (the Renderer owns it; a
// strategy only binds it): skinning and morph targets evaluated on the CPU by
// scene::AnimationPlayer and read by mesh.wgsl's SKINNED / MORPHED variants. One bind group,
// group 3 (group 2 for strategies without materials, which have no material group):
//   0  a uniform buffer of draw records, one per (instance, primitive) of every mesh with an
//      animated primitive, bound with a dynamic offset: where the primitive's morph deltas
//      start, its vertex and target counts, the instance's joint and weight offsets;
//   1  every skin's joint matrices, skin after skin (world × inverseBind, and the normal
//      matrix of each): AnimationPlayer::jointMatrices() / jointNormalMatrices();
//   2  every morphed node's weights: AnimationPlayer::morphWeights();
//   3  every morphed primitive's deltas (position, normal, tangent as vec4f, target-major);
//   4  per instance slot (InstanceBuffer order) the joint and weight offsets, for strategies
//      that index instances by instance_index.
// Only buffer contents change while playing (queue.WriteBuffer), so recorded bundles stay valid.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "encore/render/RendererStats.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"
#include "render/BindGroupLayouts.h"
#include "shaders/ShaderLibrary.h"

namespace encore::gpu {
class ResourcePool;
}

namespace encore::render {

class RenderEncoder;

class AnimationBuffers {
  public:
    // Null when the scene has neither skinned nor morphed primitives. Uploads the player's
    // current pose. `pool`: where the buffers come from (RenderSetup::resources); null: created.
    static std::unique_ptr<AnimationBuffers> create(const wgpu::Device& device,
                                                    const wgpu::Queue& queue,
                                                    const BindGroupLayouts& layouts,
                                                    const scene::SceneData& scene,
                                                    const scene::AnimationPlayer& player,
                                                    gpu::ResourcePool* pool = nullptr);
    // Hands the buffers to `pool` (the scene is being released: nothing binds them again).
    void giveBackTo(gpu::ResourcePool& pool);

    // Sets the SKINNED, SKINNED_8 and MORPHED flags that primitive `primitive` of `mesh` needs.
    void addVariantFlags(scene::MeshId mesh,
                         std::size_t primitive,
                         shaders::ShaderVariantKey& key) const;

    // Sets the animation group for drawing `primitive` of scene instance `sceneInstance` with a
    // pipeline of variant `key`; nothing when the variant is not animated.
    void bind(RenderEncoder& encoder,
              const shaders::ShaderVariantKey& key,
              std::size_t sceneInstance,
              std::size_t primitive) const;

    // Uploads what the player's last evaluate() changed: the joint matrices of changed skins and
    // the morph weights.
    AnimationUploadStats write(const wgpu::Queue& queue, const scene::AnimationPlayer& player);

    const wgpu::BindGroup& bindGroup() const { return mBindGroup; }
    // The joint matrices (binding 1) and morph weights (binding 2), with Storage, CopyDst and
    // CopySrc usage: GpuAnimation writes them in compute passes, tests read them back.
    const wgpu::Buffer& jointBuffer() const { return mJoints; }
    const wgpu::Buffer& weightBuffer() const { return mWeights; }
    std::uint32_t drawOffset(std::size_t sceneInstance, std::size_t primitive) const;
    // True when `primitive` of `mesh` is drawn skinned by the instances that have a skin.
    bool skinnedPrimitive(scene::MeshId mesh, std::size_t primitive) const;
    // The scene instance's first joint in jointBuffer() and first weight in weightBuffer()
    // (scene::InstanceAnimationRange::kNone where it has no skin or no morph targets).
    glm::uvec2 instanceOffsets(std::size_t sceneInstance) const {
        return mInstanceRanges[sceneInstance];
    }
    std::uint32_t skinnedPrimitiveCount() const { return mSkinnedPrimitives; }
    std::uint32_t morphedPrimitiveCount() const { return mMorphedPrimitives; }

  private:
    wgpu::Buffer mDraws, mJoints, mWeights, mDeltas, mInstanceOffsets;
    wgpu::BindGroup mBindGroup;
    // [mesh][primitive]: 1 skinned, 2 morphed, 4 eight joints per vertex.
    std::vector<std::vector<std::uint8_t>> mPrimitiveFlags;
    std::vector<std::uint32_t> mFirstDraw;    // Per scene instance.
    std::vector<glm::uvec2> mInstanceRanges;  // Per scene instance.
    std::vector<TransformUniform> mJointScratch;
    std::uint32_t mSkinnedPrimitives = 0;
    std::uint32_t mMorphedPrimitives = 0;
};

// Which bind group index the animation group takes in a variant's pipeline layout.
inline std::uint32_t animationGroupIndex(const shaders::ShaderVariantKey& key) {
    return key.materials ? 3u : 2u;
}

// The vertex attributes an animated variant reads besides the shading ones (joints, weights).
void appendAnimationSemantics(const shaders::ShaderVariantKey& key,
                              std::vector<scene::Semantic>& semantics);

// The vertex attributes a strategy before `materials` binds for one primitive
// (kUnlitTransformSemantics, then joints and weights where it is skinned), adding the
// primitive's animation flags to `variant`. `animation` is null when nothing is animated.
std::vector<scene::Semantic> unlitPrimitiveSemantics(const AnimationBuffers* animation,
                                                     scene::MeshId mesh,
                                                     std::size_t primitive,
                                                     shaders::ShaderVariantKey& variant);

}  // namespace encore::render
