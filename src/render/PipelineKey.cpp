#include "render/PipelineKey.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <string_view>
#include <vector>

#include "gpu/LayoutEntry.h"
#include "render/RenderSetup.h"
#include "render/SceneColorTargets.h"

namespace encore::render {

bool PipelineKey::operator==(const PipelineKey& other) const {
    return std::memcmp(this, &other, sizeof(PipelineKey)) == 0;
}

void PipelineKey::addBuffer(std::uint32_t arrayStride) {
    assert(bufferCount < kMaxBuffers);
    buffers[bufferCount++].arrayStride = arrayStride;
}

void PipelineKey::addAttribute(wgpu::VertexFormat format,
                               std::uint32_t offset,
                               std::uint32_t location) {
    assert(bufferCount > 0);
    VertexBufferKey& buffer = buffers[bufferCount - 1];
    assert(buffer.attributeCount < VertexBufferKey::kMaxAttributes);
    buffer.attributes[buffer.attributeCount++] = {format, offset, location};
}

void PipelineKey::sortLayouts() {
    for (std::uint32_t i = 0; i < bufferCount; ++i) {
        auto& buffer = buffers[i];
        std::sort(buffer.attributes, buffer.attributes + buffer.attributeCount,
                  [](const auto& a, const auto& b) { return a.shaderLocation < b.shaderLocation; });
    }
    std::sort(buffers, buffers + bufferCount, [](const auto& a, const auto& b) {
        return a.attributes[0].shaderLocation < b.attributes[0].shaderLocation;
    });
}

std::size_t PipelineKeyHash::operator()(const PipelineKey& key) const noexcept {
    return std::hash<std::string_view>{}(
        std::string_view(reinterpret_cast<const char*>(&key), sizeof(key)));
}

std::uint32_t sceneColorTargets(const shaders::ShaderVariantKey& shader) {
    return shader.materials && shader.passTargets != 0 ? kMaxSceneColorTargets : 1;
}

Result<wgpu::RenderPipeline> createMeshPipeline(const RenderSetup& setup,
                                                const PipelineKey& key,
                                                const std::string& label) {
    ENCORE_TRY_ASSIGN(auto module, setup.shaders->meshModule(key.shader));

    std::vector<wgpu::BindGroupLayout> groups = {setup.layouts->frame};
    switch (key.shader.instanceSource) {
        case shaders::InstanceSource::NodeUniform:
            groups.push_back(setup.layouts->nodeUniform);
            break;
        case shaders::InstanceSource::InstanceStorage:
            groups.push_back(setup.layouts->instanceStorage);
            break;
        case shaders::InstanceSource::VisibleList:
            groups.push_back(setup.layouts->culledInstances);
            break;
    }
    if (key.shader.materials) {
        groups.push_back(!key.shader.materialTextures    ? setup.layouts->materialUniformOnly
                         : key.shader.materialExtensions ? setup.layouts->material
                                                         : setup.layouts->materialBase);
    }
    if (key.shader.animated()) {
        groups.push_back(setup.layouts->animation);  // 3, or 2 without materials.
    }
    const wgpu::PipelineLayout layout = gpu::makePipelineLayout(setup.device, groups);

    std::vector<wgpu::VertexAttribute> attributes(PipelineKey::kMaxBuffers *
                                                  VertexBufferKey::kMaxAttributes);
    std::vector<wgpu::VertexBufferLayout> buffers(key.bufferCount);
    for (std::uint32_t b = 0; b < key.bufferCount; ++b) {
        const VertexBufferKey& bufferKey = key.buffers[b];
        wgpu::VertexAttribute* first = &attributes[b * VertexBufferKey::kMaxAttributes];
        for (std::uint32_t a = 0; a < bufferKey.attributeCount; ++a) {
            first[a].format = bufferKey.attributes[a].format;
            first[a].offset = bufferKey.attributes[a].offset;
            first[a].shaderLocation = bufferKey.attributes[a].shaderLocation;
        }
        buffers[b].arrayStride = bufferKey.arrayStride;
        buffers[b].stepMode = wgpu::VertexStepMode::Vertex;
        buffers[b].attributeCount = bufferKey.attributeCount;
        buffers[b].attributes = first;
    }

    wgpu::BlendState blend{};
    blend.color = {wgpu::BlendOperation::Add, wgpu::BlendFactor::SrcAlpha,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    blend.alpha = {wgpu::BlendOperation::Add, wgpu::BlendFactor::One,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    // With pass targets, the pass images blend as the colour does (render/PassTargets.h).
    std::array<wgpu::ColorTargetState, kMaxSceneColorTargets> colorTargets{};
    for (wgpu::ColorTargetState& colorTarget : colorTargets) {
        colorTarget.format = key.colorFormat;
        colorTarget.blend = key.blend ? &blend : nullptr;
    }
    wgpu::FragmentState fragment{};
    fragment.module = module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = sceneColorTargets(key.shader);
    fragment.targets = colorTargets.data();

    wgpu::DepthStencilState depth{};
    depth.format = key.depthFormat;
    depth.depthWriteEnabled = wgpu::OptionalBool::True;
    depth.depthCompare = wgpu::CompareFunction::Less;

    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = label.c_str();
    descriptor.layout = layout;
    descriptor.vertex.module = module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.vertex.bufferCount = buffers.size();
    descriptor.vertex.buffers = buffers.data();
    descriptor.primitive.topology = key.topology;
    descriptor.primitive.stripIndexFormat = key.stripIndexFormat;
    descriptor.primitive.cullMode = key.cullMode;
    descriptor.primitive.frontFace = key.frontFace;
    descriptor.depthStencil = &depth;
    descriptor.multisample.count = key.sampleCount;
    descriptor.fragment = &fragment;
    ++setup.pipelinesCreated;
    return setup.device.CreateRenderPipeline(&descriptor);
}

}  // namespace encore::render
