#include "render/FrameUniforms.h"

#include <cstring>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/BindingResource.h"
#include "gpu/Upload.h"

namespace encore::render {

FrameUniforms::FrameUniforms(const wgpu::Device& device,
                             const BindGroupLayouts& layouts,
                             const SceneLighting& lighting) {
    // CopySrc: the visibility strategy copies each view's into the slot its shading reads.
    mBuffer = gpu::createBuffer(
        device,
        wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
        sizeof(FrameUniform), "frame uniforms");
    bindLighting(device, layouts, lighting);
}

void FrameUniforms::bindLighting(const wgpu::Device& device,
                                 const BindGroupLayouts& layouts,
                                 const SceneLighting& lighting) {
    const Environment& environment = lighting.environment();
    mBindGroup =
        gpu::makeBindGroup(device, layouts.frame,
                           {{0, mBuffer, 0, sizeof(FrameUniform)},
                            {1, lighting.uniformBuffer(), 0, sizeof(LightingUniform)},
                            {2, lighting.lightBuffer(), 0, lighting.lightBuffer().GetSize()},
                            {3, environment.atlasView()},
                            {4, environment.sampler()},
                            {5, mTransmission ? mTransmission : environment.atlasView()}},
                           "frame");
}

void FrameUniforms::bindTransmission(const wgpu::Device& device,
                                     const BindGroupLayouts& layouts,
                                     const SceneLighting& lighting,
                                     wgpu::TextureView background) {
    if (background.Get() == mTransmission.Get()) {
        return;  // Bundles recorded with the current bind group stay valid.
    }
    mTransmission = std::move(background);
    bindLighting(device, layouts, lighting);
}

FrameUniform frameUniformOf(const Camera& camera,
                            float timeSeconds,
                            std::size_t view,
                            std::size_t viewCount) {
    FrameUniform uniform{};
    const float width = 1.0f / float(viewCount);
    uniform.viewRect[0] = float(view) * width;
    uniform.viewRect[1] = 0.0f;
    uniform.viewRect[2] = width;
    uniform.viewRect[3] = 1.0f;
    std::memcpy(uniform.projection, glm::value_ptr(camera.projection), sizeof(uniform.projection));
    std::memcpy(uniform.view, glm::value_ptr(camera.view), sizeof(uniform.view));
    std::memcpy(uniform.cameraPosition, glm::value_ptr(camera.position),
                sizeof(uniform.cameraPosition));
    uniform.time = timeSeconds;
    return uniform;
}

void FrameUniforms::update(const wgpu::Queue& queue,
                           const Camera& camera,
                           float timeSeconds) const {
    const FrameUniform uniform = frameUniformOf(camera, timeSeconds);
    queue.WriteBuffer(mBuffer, 0, &uniform, sizeof(uniform));
}

void FrameUniforms::writeViews(const wgpu::Device& device,
                               const wgpu::Queue& queue,
                               std::span<const Camera> cameras,
                               float timeSeconds) {
    const std::uint64_t size = kViewStride * cameras.size();
    if (!mViews || mViews.GetSize() < size) {
        mViews = gpu::createBuffer(device, wgpu::BufferUsage::CopySrc | wgpu::BufferUsage::CopyDst,
                                   size, "view cameras");
    }
    std::vector<std::uint8_t> bytes(size, 0);
    for (std::size_t view = 0; view < cameras.size(); ++view) {
        const FrameUniform uniform =
            frameUniformOf(cameras[view], timeSeconds, view, cameras.size());
        std::memcpy(bytes.data() + view * kViewStride, &uniform, sizeof(uniform));
    }
    queue.WriteBuffer(mViews, 0, bytes.data(), bytes.size());
}

void FrameUniforms::selectView(const wgpu::CommandEncoder& commands, std::size_t view) const {
    commands.CopyBufferToBuffer(mViews, view * kViewStride, mBuffer, 0, sizeof(FrameUniform));
}

}  // namespace encore::render
