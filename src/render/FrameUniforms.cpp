#include "encore/render/FrameUniforms.h"

#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "encore/gpu/Upload.h"

namespace encore::render {

FrameUniforms::FrameUniforms(const wgpu::Device& device, const BindGroupLayouts& layouts) {
    mBuffer = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                sizeof(FrameUniform), "frame uniforms");
    wgpu::BindGroupEntry entry{};
    entry.binding = 0;
    entry.buffer = mBuffer;
    entry.size = sizeof(FrameUniform);
    wgpu::BindGroupDescriptor descriptor{};
    descriptor.label = "frame";
    descriptor.layout = layouts.frame;
    descriptor.entryCount = 1;
    descriptor.entries = &entry;
    mBindGroup = device.CreateBindGroup(&descriptor);
}

void FrameUniforms::update(const wgpu::Queue& queue, const Camera& camera,
                           float timeSeconds) const {
    FrameUniform uniform{};
    std::memcpy(uniform.projection, glm::value_ptr(camera.projection), sizeof(uniform.projection));
    std::memcpy(uniform.view, glm::value_ptr(camera.view), sizeof(uniform.view));
    std::memcpy(uniform.cameraPosition, glm::value_ptr(camera.position),
                sizeof(uniform.cameraPosition));
    uniform.time = timeSeconds;
    queue.WriteBuffer(mBuffer, 0, &uniform, sizeof(uniform));
}

}  // namespace encore::render
