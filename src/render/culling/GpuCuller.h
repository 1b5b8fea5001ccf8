#pragma once

// GPU culling feeding indirect draws (after toji's webgpu-bundle-culling, without its
// per-drawable buffers), with levels of detail and two-phase occlusion culling (Haar and
// Aaltonen, "GPU-Driven Rendering Pipelines", SIGGRAPH 2015). For N culled primitives, each
// covering one instance range of the InstanceBuffer and drawn at one of its levels of detail:
//  - one indirect-arguments buffer holds one argument record per (primitive, level, phase) (one
//    buffer, because Dawn validates indirect draws per buffer); firstInstance is always 0;
//  - one visible-instance buffer holds one list per record, each starting at a 256-byte
//    aligned entry so a dynamic offset of the group 1 bind group selects it per draw;
//  - each frame a compute pass zeroes every instanceCount, bounds every instance where this
//    frame's transforms put it (CullingBounds: world matrices from the InstanceBuffer, joint
//    matrices and morph weights from AnimationBuffers), tests that against the frustum, picks
//    each primitive's level from the error its simplification projects on the screen, and
//    appends the instance to that level's list: phase 1 takes what was visible last frame;
//  - after phase 1 is drawn, a depth pyramid (DepthPyramid) is reduced from its depth and a
//    second pass tests every instance in the frustum against it: phase 2 draws the visible ones
//    phase 1 did not, and each instance's visibility is kept for the next frame.
// The draw count never changes; only instance counts do, so recorded bundles stay valid, and
// nothing on the CPU follows moved or animated instances. The culling passes also count the
// triangles the frame draws (trianglesDrawnOffset).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/Camera.h"
#include "encore/render/RendererOptions.h"
#include "gpu/GpuTimer.h"
#include "render/AnimationBuffers.h"
#include "render/InstanceBuffer.h"
#include "render/RenderSetup.h"
#include "render/culling/CullingBounds.h"
#include "render/culling/DepthPyramid.h"
#include "render/culling/Frustum.h"
#include "render/culling/LodSelection.h"

namespace encore::render {

// A coarser level of detail of an indexed primitive: a range of its index buffer.
struct DrawLevel {
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    float error = 0.0f;  // Object-space simplification error.
};

struct CulledDraw {
    InstanceRange instances;  // Slots of the InstanceBuffer this draw may show.
    bool indexed = true;
    std::uint32_t elementCount = 0;  // Indices, or vertices when not indexed (level 0).
    scene::Topology topology = scene::Topology::TriangleList;  // What the triangle counts count.
    // Finer to coarser, each with a larger error; empty without levels of detail.
    std::vector<DrawLevel> coarserLevels;

    std::uint32_t levelCount() const {
        return 1 + static_cast<std::uint32_t>(coarserLevels.size());
    }
};

// What `draws` could draw with every instance visible at full detail: the sum of each draw's
// level-0 triangles x its instance count. The CPU side of the culling pass's count, and the
// triangles "submitted" by the indirect draws in benchmark reports.
std::uint64_t submittedTriangles(std::span<const CulledDraw> draws);

// What the first culling pass of a frame tests against.
struct CullingView {
    Camera camera;
    // All views of a multi-view frame, which one cull serves (`camera` is one of them); empty or
    // one for a frame of one view.
    std::span<const Camera> views;
    std::uint32_t targetWidth = 0;  // Pixels, for the projected error of levels of detail.
    std::uint32_t targetHeight = 0;
    CullingOptions options;
    // Two phases follow (encodeSecondPhase): the first takes only what was visible last frame.
    bool twoPhases = false;
};

class GpuCuller {
  public:
    static constexpr std::uint64_t kArgumentsStride = 20;  // Five u32: the indexed layout.
    static constexpr std::uint32_t kPhases = 2;
    // Views of a multi-view frame whose positions levels of detail are chosen from
    // (culling.wgsl's lodViews); a frame of more uses a bound around them.
    static constexpr std::size_t kMaxLodViews = LodSelection::kMaxViews;

    GpuCuller() = default;
    // `bounds` has one record per instance slot; `animation` (when not null) supplies the
    // joint matrices and morph weights they refer to.
    static Result<GpuCuller> create(const RenderSetup& setup,
                                    const InstanceBuffer& instances,
                                    const AnimationBuffers* animation,
                                    CullingBounds bounds,
                                    std::vector<CulledDraw> draws);

    // Writes the view's culling uniform and records the reset and the first phase's cull.
    void encodeFirstPhase(const wgpu::Queue& queue,
                          const wgpu::CommandEncoder& commands,
                          const CullingView& view,
                          gpu::GpuTimer* timer = nullptr);
    // After phase 1 is drawn into `depth`: reduces the depth pyramid and records the second
    // phase's cull (a pyramid is made for each new depth texture).
    void encodeSecondPhase(const wgpu::CommandEncoder& commands,
                           const wgpu::Texture& depth,
                           gpu::GpuTimer* timer = nullptr);

    const std::vector<CulledDraw>& draws() const { return mDraws; }
    const CullingBounds& bounds() const { return mBounds; }
    const wgpu::Buffer& indirectArguments() const { return mArguments; }
    // The indirect draw of `draw` at `level` in `phase` (0 or 1).
    std::uint64_t argumentsOffset(std::size_t draw,
                                  std::uint32_t level = 0,
                                  std::uint32_t phase = 0) const {
        return (phase * std::uint64_t(mLevelDrawCount) + mFirstLevel[draw] + level) *
               kArgumentsStride;
    }
    // Group 1 for that draw: bind with its dynamicOffset.
    const wgpu::BindGroup& drawBindGroup() const { return mDrawBindGroup; }
    std::uint32_t dynamicOffset(std::size_t draw,
                                std::uint32_t level = 0,
                                std::uint32_t phase = 0) const {
        return (mVisibleBase[mFirstLevel[draw] + level] + phase * mPhaseVisible) * 4;
    }
    // Where in indirectArguments() (CopySrc) the triangles the last culled frame drew lie: one
    // u32 after the last argument record, the sum over both phases of every appended instance's
    // triangles at its level. The reset zeroes it each frame; copy it out after the frame's
    // last pass (Renderer::setTriangleCounting). It shares the arguments' binding because the
    // culling pass already binds the 8 storage buffers a device offers by default. 32 bits
    // hold it: a million objects of tessellation 16 are about 5 x 10^8 triangles, under 2^32;
    // a scene with more wraps around.
    std::uint64_t drawnTrianglesOffset() const { return mTrianglesDrawnWord * 4ull; }
    // The pyramid the last two-phase frame built (empty before one).
    const DepthPyramid& depthPyramid() const { return mPyramid; }

  private:
    // Creates the culling pass's bind group (culling.wgsl's group 0) with the buffers only it
    // binds: the slots' bounds, their joint spheres and morph extents, the draw and level
    // records.
    void bindCulling(const wgpu::BindGroupLayout& cullLayout,
                     const InstanceBuffer& instances,
                     const AnimationBuffers* animation,
                     std::span<const glm::uvec4> drawRecords,
                     std::uint64_t argumentBytes);

    RenderSetup const* mSetup = nullptr;
    std::vector<CulledDraw> mDraws;
    CullingBounds mBounds;
    std::vector<std::uint32_t> mFirstLevel;   // Per draw: its first level draw.
    std::vector<std::uint32_t> mVisibleBase;  // Per level draw, in entries (phase 1).
    std::uint32_t mLevelDrawCount = 0;
    std::uint32_t mPhaseVisible = 0;  // Entries from a phase 1 list to its phase 2 list.
    std::uint32_t mTrianglesDrawnWord = 0;
    std::uint32_t mLevelBase = 0;  // The first level record, after the primitives'.
    wgpu::Buffer mUniform;
    wgpu::Buffer mArguments;
    wgpu::Buffer mVisible;
    wgpu::BindGroup mDrawBindGroup;
    wgpu::BindGroup mCullBindGroup;
    wgpu::BindGroupLayout mPyramidLayout;
    wgpu::BindGroup mPyramidBindGroup;
    wgpu::ComputePipeline mReset;
    wgpu::ComputePipeline mCullFirst;
    wgpu::ComputePipeline mCullSecond;
    DepthPyramid mPyramid;
    std::uint32_t mSlotCount = 0;
};

}  // namespace encore::render
