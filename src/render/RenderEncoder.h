#pragma once

// The one interface strategies record through. It forwards to a render pass encoder or a render
// bundle encoder — the same recording code serves both, as in the WebGPU samples — and counts
// every call in DrawCounters.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <span>
#include <vector>

#include "encore/render/RendererStats.h"
#include "encore/scene/SceneData.h"

namespace encore::render {

// One recorded call, for tests that check the order of calls rather than only their number.
struct RecordedCall {
    enum class Kind {
        SetPipeline,
        SetBindGroup,
        SetVertexBuffer,
        SetIndexBuffer,
        Draw,
        ExecuteBundles
    };
    Kind kind;
    const void* object = nullptr;  // The pipeline, bind group or buffer handle.
    std::uint32_t index = 0;       // Bind group index or vertex buffer slot.
};

class RenderEncoder {
  public:
    RenderEncoder(const wgpu::RenderPassEncoder& pass, DrawCounters& counters)
        : mPass(pass), mCounters(counters) {}
    RenderEncoder(const wgpu::RenderBundleEncoder& bundle, DrawCounters& counters)
        : mBundle(bundle), mCounters(counters) {}

    bool recordsBundle() const { return bool(mBundle); }

    void setPipeline(const wgpu::RenderPipeline& pipeline);
    void setBindGroup(std::uint32_t index,
                      const wgpu::BindGroup& group,
                      std::uint32_t dynamicOffset);
    void setBindGroup(std::uint32_t index, const wgpu::BindGroup& group);
    void setVertexBuffer(std::uint32_t slot,
                         const wgpu::Buffer& buffer,
                         std::uint64_t offset = 0,
                         std::uint64_t size = wgpu::kWholeSize);
    void setIndexBuffer(const wgpu::Buffer& buffer,
                        wgpu::IndexFormat format,
                        std::uint64_t offset = 0,
                        std::uint64_t size = wgpu::kWholeSize);
    // `topology` only feeds the triangle counter.
    void draw(std::uint32_t vertexCount,
              std::uint32_t instanceCount,
              std::uint32_t firstVertex,
              std::uint32_t firstInstance,
              scene::Topology topology);
    void drawIndexed(std::uint32_t indexCount,
                     std::uint32_t instanceCount,
                     std::uint32_t firstIndex,
                     std::int32_t baseVertex,
                     std::uint32_t firstInstance,
                     scene::Topology topology);
    void drawIndirect(const wgpu::Buffer& buffer, std::uint64_t offset);
    void drawIndexedIndirect(const wgpu::Buffer& buffer, std::uint64_t offset);
    // Render passes only: replays recorded bundles (state is reset before and after).
    void executeBundles(std::span<const wgpu::RenderBundle> bundles);

    DrawCounters& counters() { return mCounters; }
    // Also appends every call to `trace` (nullptr: no trace).
    void setTrace(std::vector<RecordedCall>* trace) { mTrace = trace; }

  private:
    void record(RecordedCall::Kind kind, const void* object, std::uint32_t index = 0) {
        if (mTrace) {
            mTrace->push_back({kind, object, index});
        }
    }

    wgpu::RenderPassEncoder mPass;
    wgpu::RenderBundleEncoder mBundle;
    DrawCounters& mCounters;
    std::vector<RecordedCall>* mTrace = nullptr;
};

using scene::triangleCount;  // The counters count what the scene's primitives draw.

}  // namespace encore::render
