#pragma once

// GpuAnimation evaluates a scene's animations on the GPU, the alternative to
// scene::AnimationPlayer's CPU evaluation (AnimationEvaluation::Gpu). Every sampler's key times
// and outputs go into one storage buffer when it is created (each distinct run once, so copies of
// one model share them); each frame the CPU writes only the
// time of each clock (one per distinct animation duration; each animation adds its own time
// offset on the GPU) and records a fixed number of compute dispatches:
//   1. animation_sample.wgsl: per animated node, samples the selected channels (binary search
//      over the key times; STEP, LINEAR with normalised shortest-path slerp for rotations,
//      CUBICSPLINE with tangents scaled by the key interval) into its local matrix and morph
//      weights (AnimationBuffers' weight buffer, at the player's offsets);
//   2. animation_world.wgsl: world matrices of the nodes at or below an animated node, one
//      dispatch per depth level, parents first; other nodes keep their rest world matrix;
//   3. animation_transforms.wgsl: instance world and normal matrices into the GPU scene's
//      instance transforms (for strategies with a uniform buffer per node, then copied to each
//      node's buffer), and joint matrices (world × inverseBind,
//      with their normal matrices) into AnimationBuffers' joint buffer.
// The results land in the same buffers at the same offsets as the CPU path's uploads, so the
// vertex shaders and recorded bundles are unchanged. The CPU cost of a frame depends on the
// number of animations and hierarchy levels, not on the number of animated nodes (except the
// per-node copies of the node-uniform strategies, which draw per node anyway).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/gpu/DeviceLimits.h"
#include "encore/render/RendererStats.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"
#include "render/InstanceTransformTargets.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

class AnimationBuffers;
struct AnimationTables;

class GpuAnimation {
  public:
    // An error (LimitExceeded) when one of its storage buffers would exceed the device's limits,
    // or a dispatch the number of workgroups WebGPU allows.
    static Result<void> checkLimits(const gpu::DeviceLimits& limits, const scene::SceneData& scene);

    // Null when the scene has no animation. `animation` (the scene's AnimationBuffers; null
    // when it has neither skins nor morph targets) and `instances` (the GPU scene's instance
    // transforms: InstanceBuffer::transformTargets) must outlive the returned object. Every
    // animation is selected. Built once per GPU scene, whichever strategy draws it.
    static Result<std::unique_ptr<GpuAnimation>> create(const wgpu::Device& device,
                                                        const wgpu::Queue& queue,
                                                        shaders::ShaderLibrary& shaders,
                                                        const gpu::DeviceLimits& limits,
                                                        const scene::SceneData& scene,
                                                        const AnimationBuffers* animation,
                                                        const InstanceTransformTargets& instances);

    // For strategies that keep transforms of their own (InstanceTransformTargets::uniforms, one
    // uniform buffer per scene instance): after the passes, every moved instance's transform is
    // also copied there. Empty: no copies.
    void copyInstancesTo(std::span<const wgpu::Buffer> uniforms);

    // Which animations play: of channels driving the same property, the later animation's wins
    // (as AnimationPlayer). Writes one small table; call when the selection changes.
    void select(const wgpu::Queue& queue, std::span<const scene::AnimationId> selection);

    // Writes each clock's time at `seconds` (wrapped in PlaybackMode::Loop exactly as
    // AnimationPlayer wraps); the passes add each animation's time offset and wrap once more.
    void setTime(const wgpu::Queue& queue, double seconds, scene::PlaybackMode mode);

    // Records the frame's compute passes (and copies) into `commands`; submit them before the
    // render pass that draws with the results.
    void encode(const wgpu::CommandEncoder& commands) const;

    const GpuAnimationStats& stats() const { return mStats; }
    // Node local and world matrices (mat4x4f per node, CopySrc), for tests and tools.
    const wgpu::Buffer& locals() const { return mLocals; }
    const wgpu::Buffer& worlds() const { return mWorlds; }

  private:
    GpuAnimation() = default;
    // Keeps what select(), encode() and copyInstancesTo() index.
    void keepIndices(const AnimationTables& tables);
    void countStats(const AnimationTables& tables);
    // Every node's local and world matrices, at rest.
    void createNodeMatrices(const wgpu::Device& device, const scene::SceneData& scene);
    Result<void> createPipelines(const wgpu::Device& device, shaders::ShaderLibrary& shaders);
    // The bind group(s) of each pass, with the buffers only that pass binds.
    void bindSampling(const wgpu::Device& device,
                      AnimationTables& tables,
                      const AnimationBuffers* animation);
    void bindWorldLevels(const wgpu::Device& device,
                         const gpu::DeviceLimits& limits,
                         const AnimationTables& tables);
    void bindTransforms(const wgpu::Device& device,
                        const AnimationTables& tables,
                        const AnimationBuffers* animation,
                        const InstanceTransformTargets& instances);

    const scene::SceneData* mScene = nullptr;
    std::vector<std::uint32_t> mAnimatedNodes;   // Node index per pass-1 thread.
    std::vector<std::uint32_t> mInstances;       // Scene instances written.
    std::vector<std::uint32_t> mSamplerOffsets;  // First GPU sampler of each animation.
    std::vector<float> mClockEnds;   // Per clock: the duration of the animations that share it.
    std::vector<float> mClockTimes;  // The playback-mode header, then per clock, by setTime.
    bool mModeWritten = false;
    wgpu::Buffer mClocks, mNodeChannels, mLocals, mWorlds;
    wgpu::Buffer mInstanceOutput;  // The GPU scene's instance transforms.
    wgpu::ComputePipeline mSample, mWorld, mTransform;
    wgpu::BindGroup mSampleGroup, mInstanceGroup, mJointGroup;
    std::vector<wgpu::BindGroup> mLevelGroups;
    std::vector<std::uint32_t> mLevelCounts;
    std::uint32_t mInstanceRecords = 0;
    std::uint32_t mJointRecords = 0;
    std::vector<std::uint32_t> mInstanceSlots;  // Where mInstances[k] lives in the output.
    // Node-uniform strategies: copy record k from mInstanceOutput to mCopyTargets[k].
    std::vector<wgpu::Buffer> mCopyTargets;
    GpuAnimationStats mStats;
};

}  // namespace encore::render
