#pragma once

// GPU frustum culling feeding indirect draws (after toji's webgpu-bundle-culling, without its
// per-drawable buffers). For N draws, each covering one instance range of the InstanceBuffer:
//  - one indirect-arguments buffer holds all N argument records (one buffer, because Dawn
//    validates indirect draws per buffer); firstInstance is always 0;
//  - one visible-instance buffer holds N lists, each starting at a 256-byte aligned entry so a
//    dynamic offset of the group 1 bind group selects it per draw;
//  - each frame a compute pass zeroes every instanceCount, bounds every instance where this
//    frame's transforms put it (CullingBounds: world matrices from the InstanceBuffer, joint
//    matrices and morph weights from AnimationBuffers), tests that against the frustum and
//    appends visible instances to the lists of its mesh's draws;
//  - the same pass counts the triangles it lets through (drawnTrianglesOffset()): per appended
//    (instance, draw), the draw's triangles.
// The draw count never changes; only instance counts do, so recorded bundles stay valid, and
// nothing on the CPU follows moved or animated instances.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <vector>

#include "encore/core/Result.h"
#include "encore/render/Camera.h"
#include "encore/render/CullingBounds.h"
#include "encore/render/Frustum.h"
#include "encore/render/InstanceBuffer.h"
#include "encore/render/Strategy.h"

namespace encore::render {

struct CulledDraw {
    InstanceRange instances;  // Slots of the InstanceBuffer this draw may show.
    bool indexed = true;
    std::uint32_t elementCount = 0;  // Indices, or vertices when not indexed.
    // What one instance of the draw draws: triangleCount(topology, elementCount).
    std::uint32_t triangles = 0;
};

// What `draws` could draw with every instance visible: the sum of triangles x instance count.
// The CPU side of the culling pass's count (GpuCuller::drawnTriangles), and the triangles
// "submitted" by the indirect draws in benchmark reports.
std::uint64_t submittedTriangles(std::span<const CulledDraw> draws);

class GpuCuller {
  public:
    static constexpr std::uint64_t kArgumentsStride = 20;  // Five u32: the indexed layout.

    GpuCuller() = default;
    // `bounds` has one record per instance slot; setup.animation (when not null) supplies the
    // joint matrices and morph weights they refer to.
    static Result<GpuCuller> create(const RenderSetup& setup, const InstanceBuffer& instances,
                                    CullingBounds bounds, std::vector<CulledDraw> draws);

    // Writes the camera's frustum and records the reset and cull dispatches.
    void encode(const wgpu::Queue& queue, const wgpu::CommandEncoder& commands,
                const Camera& camera, gpu::GpuTimer* timer = nullptr) const;

    const std::vector<CulledDraw>& draws() const { return mDraws; }
    const CullingBounds& bounds() const { return mBounds; }
    const wgpu::Buffer& indirectArguments() const { return mArguments; }
    std::uint64_t argumentsOffset(std::size_t draw) const { return draw * kArgumentsStride; }
    // Group 1 for draw `draw`: bind with dynamicOffset(draw).
    const wgpu::BindGroup& drawBindGroup() const { return mDrawBindGroup; }
    std::uint32_t dynamicOffset(std::size_t draw) const { return mVisibleBase[draw] * 4; }
    // Where in indirectArguments() (CopySrc) the triangles the last cull let through lie: one
    // u32 after the last argument record, the sum over visible instances of their draws'
    // triangles. The reset dispatch zeroes it each frame; copy it out after encode()
    // (Renderer::setTriangleCounting). It shares the arguments' binding because the culling
    // pass already binds the 8 storage buffers a device offers by default. 32 bits hold it: a
    // million objects of tessellation 16 are about 5 x 10^8 triangles, under 2^32 (4.3 x 10^9);
    // a scene with more wraps around.
    std::uint64_t drawnTrianglesOffset() const { return mDraws.size() * kArgumentsStride; }

  private:
    std::vector<CulledDraw> mDraws;
    CullingBounds mBounds;
    std::vector<std::uint32_t> mVisibleBase;  // Per draw, in entries.
    wgpu::Buffer mFrustum;
    wgpu::Buffer mArguments;
    wgpu::Buffer mVisible;
    wgpu::BindGroup mDrawBindGroup;
    wgpu::BindGroup mCullBindGroup;
    wgpu::ComputePipeline mReset;
    wgpu::ComputePipeline mCull;
    std::uint32_t mSlotCount = 0;
};

}  // namespace encore::render
