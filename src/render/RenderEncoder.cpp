#include "render/RenderEncoder.h"

#include <cassert>

namespace encore::render {

DrawCounters& DrawCounters::operator+=(const DrawCounters& other) {
    setPipeline += other.setPipeline;
    setBindGroup += other.setBindGroup;
    setVertexBuffer += other.setVertexBuffer;
    setIndexBuffer += other.setIndexBuffer;
    draw += other.draw;
    drawIndexed += other.drawIndexed;
    drawIndirect += other.drawIndirect;
    executeBundles += other.executeBundles;
    primitives += other.primitives;
    instances += other.instances;
    triangles += other.triangles;
    return *this;
}

// Each call goes to whichever encoder this wraps; the branch is negligible next to the call.
#define ENCORE_FORWARD(call) \
    do {                     \
        if (mPass) {         \
            mPass.call;      \
        } else {             \
            mBundle.call;    \
        }                    \
    } while (false)

void RenderEncoder::setPipeline(const wgpu::RenderPipeline& pipeline) {
    ++mCounters.setPipeline;
    record(RecordedCall::Kind::SetPipeline, pipeline.Get());
    ENCORE_FORWARD(SetPipeline(pipeline));
}

void RenderEncoder::setBindGroup(std::uint32_t index,
                                 const wgpu::BindGroup& group,
                                 std::uint32_t dynamicOffset) {
    ++mCounters.setBindGroup;
    record(RecordedCall::Kind::SetBindGroup, group.Get(), index);
    ENCORE_FORWARD(SetBindGroup(index, group, 1, &dynamicOffset));
}

void RenderEncoder::setBindGroup(std::uint32_t index, const wgpu::BindGroup& group) {
    ++mCounters.setBindGroup;
    record(RecordedCall::Kind::SetBindGroup, group.Get(), index);
    ENCORE_FORWARD(SetBindGroup(index, group, 0, nullptr));
}

void RenderEncoder::setVertexBuffer(std::uint32_t slot,
                                    const wgpu::Buffer& buffer,
                                    std::uint64_t offset,
                                    std::uint64_t size) {
    ++mCounters.setVertexBuffer;
    record(RecordedCall::Kind::SetVertexBuffer, buffer.Get(), slot);
    ENCORE_FORWARD(SetVertexBuffer(slot, buffer, offset, size));
}

void RenderEncoder::setIndexBuffer(const wgpu::Buffer& buffer,
                                   wgpu::IndexFormat format,
                                   std::uint64_t offset,
                                   std::uint64_t size) {
    ++mCounters.setIndexBuffer;
    record(RecordedCall::Kind::SetIndexBuffer, buffer.Get());
    ENCORE_FORWARD(SetIndexBuffer(buffer, format, offset, size));
}

void RenderEncoder::draw(std::uint32_t vertexCount,
                         std::uint32_t instanceCount,
                         std::uint32_t firstVertex,
                         std::uint32_t firstInstance,
                         scene::Topology topology) {
    ++mCounters.draw;
    record(RecordedCall::Kind::Draw, nullptr);
    ++mCounters.primitives;
    mCounters.instances += instanceCount;
    mCounters.triangles += triangleCount(topology, vertexCount) * instanceCount;
    ENCORE_FORWARD(Draw(vertexCount, instanceCount, firstVertex, firstInstance));
}

void RenderEncoder::drawIndexed(std::uint32_t indexCount,
                                std::uint32_t instanceCount,
                                std::uint32_t firstIndex,
                                std::int32_t baseVertex,
                                std::uint32_t firstInstance,
                                scene::Topology topology) {
    ++mCounters.drawIndexed;
    record(RecordedCall::Kind::Draw, nullptr);
    ++mCounters.primitives;
    mCounters.instances += instanceCount;
    mCounters.triangles += triangleCount(topology, indexCount) * instanceCount;
    ENCORE_FORWARD(DrawIndexed(indexCount, instanceCount, firstIndex, baseVertex, firstInstance));
}

void RenderEncoder::drawIndirect(const wgpu::Buffer& buffer, std::uint64_t offset) {
    ++mCounters.drawIndirect;
    ++mCounters.primitives;
    record(RecordedCall::Kind::Draw, buffer.Get());
    ENCORE_FORWARD(DrawIndirect(buffer, offset));
}

void RenderEncoder::drawIndexedIndirect(const wgpu::Buffer& buffer, std::uint64_t offset) {
    ++mCounters.drawIndirect;
    ++mCounters.primitives;
    record(RecordedCall::Kind::Draw, buffer.Get());
    ENCORE_FORWARD(DrawIndexedIndirect(buffer, offset));
}

void RenderEncoder::executeBundles(std::span<const wgpu::RenderBundle> bundles) {
    assert(mPass && "bundles execute only in render passes");
    ++mCounters.executeBundles;
    record(RecordedCall::Kind::ExecuteBundles, nullptr, static_cast<std::uint32_t>(bundles.size()));
    mPass.ExecuteBundles(bundles.size(), bundles.data());
}

#undef ENCORE_FORWARD

}  // namespace encore::render
