#include "view/Overlay.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"

// stb_easy_font's functions are static; the ones this file does not call would warn.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace encore::view {

namespace {

// stb_easy_font writes 4 vertices per quad of 16 bytes each: x, y, z floats and a colour.
struct EasyFontVertex {
    float x, y, z;
    unsigned char color[4];
};
static_assert(sizeof(EasyFontVertex) == 16);

constexpr std::uint64_t kInitialVertexCapacity = 16384;

}  // namespace

Result<Overlay> Overlay::create(const wgpu::Device& device,
                                const wgpu::Queue& queue,
                                shaders::ShaderLibrary& shaders,
                                wgpu::TextureFormat surfaceFormat) {
    ENCORE_TRY_ASSIGN(auto module, shaders.module("overlay.wgsl"));
    Overlay overlay;
    overlay.mDevice = device;
    overlay.mQueue = queue;

    const wgpu::BindGroupLayout layout = gpu::makeBindGroupLayout(
        device, {gpu::LayoutEntry::uniform(0, wgpu::ShaderStage::Vertex, 16)}, "overlay");

    wgpu::VertexAttribute attributes[2]{};
    attributes[0].format = wgpu::VertexFormat::Float32x2;
    attributes[0].offset = 0;
    attributes[0].shaderLocation = 0;
    attributes[1].format = wgpu::VertexFormat::Unorm8x4;
    attributes[1].offset = 8;
    attributes[1].shaderLocation = 1;
    wgpu::VertexBufferLayout vertexLayout{};
    vertexLayout.arrayStride = sizeof(Vertex);
    vertexLayout.attributeCount = 2;
    vertexLayout.attributes = attributes;

    wgpu::BlendState blend{};
    blend.color = {wgpu::BlendOperation::Add, wgpu::BlendFactor::SrcAlpha,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    blend.alpha = {wgpu::BlendOperation::Add, wgpu::BlendFactor::One,
                   wgpu::BlendFactor::OneMinusSrcAlpha};
    wgpu::ColorTargetState color{};
    color.format = surfaceFormat;
    color.blend = &blend;
    wgpu::FragmentState fragment{};
    fragment.module = module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &color;
    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "overlay";
    descriptor.layout = gpu::makePipelineLayout(device, {layout});
    descriptor.vertex.module = module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.vertex.bufferCount = 1;
    descriptor.vertex.buffers = &vertexLayout;
    descriptor.fragment = &fragment;
    overlay.mPipeline = device.CreateRenderPipeline(&descriptor);

    overlay.mViewport = gpu::createBuffer(
        device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst, 16, "overlay viewport");
    overlay.mBindGroup =
        gpu::makeBindGroup(device, layout, {{0, overlay.mViewport, 0, 16}}, "overlay");
    return overlay;
}

glm::vec2 Overlay::measureText(std::string_view text, float scale) {
    std::string copy(text);
    return glm::vec2(float(stb_easy_font_width(copy.data())),
                     float(stb_easy_font_height(copy.data()))) *
           scale;
}

glm::vec2 Overlay::addText(float x,
                           float y,
                           std::string_view text,
                           OverlayColor color,
                           float scale) {
    std::string copy(text);
    // About 270 bytes per character is stb_easy_font's worst case.
    std::vector<EasyFontVertex> quads(copy.size() * 70 + 4);
    unsigned char rgba[4] = {color.r, color.g, color.b, color.a};
    const int quadCount = stb_easy_font_print(0.0f, 0.0f, copy.data(), rgba, quads.data(),
                                              int(quads.size() * sizeof(EasyFontVertex)));
    for (int quad = 0; quad < quadCount; ++quad) {
        glm::vec2 corners[4];
        for (int corner = 0; corner < 4; ++corner) {
            const EasyFontVertex& vertex = quads[std::size_t(quad) * 4 + std::size_t(corner)];
            corners[corner] = glm::vec2(x, y) + glm::vec2(vertex.x, vertex.y) * scale;
        }
        addQuad(corners, color);
    }
    return measureText(text, scale);
}

void Overlay::addRectangle(float x, float y, float width, float height, OverlayColor color) {
    const glm::vec2 corners[4] = {{x, y}, {x + width, y}, {x + width, y + height}, {x, y + height}};
    addQuad(corners, color);
}

void Overlay::addLine(glm::vec2 from, glm::vec2 to, float thickness, OverlayColor color) {
    const glm::vec2 along = to - from;
    const float length = std::sqrt(glm::dot(along, along));
    if (!(length > 0.0f) || !std::isfinite(length)) {
        return;
    }
    const glm::vec2 side = glm::vec2(-along.y, along.x) / length * (0.5f * thickness);
    const glm::vec2 corners[4] = {from - side, to - side, to + side, from + side};
    addQuad(corners, color);
}

void Overlay::addQuad(const glm::vec2 corners[4], OverlayColor color) {
    for (int index : {0, 1, 2, 0, 2, 3}) {
        mVertices.push_back({corners[index].x, corners[index].y, color});
    }
}

void Overlay::encode(const wgpu::CommandEncoder& commands,
                     const wgpu::TextureView& target,
                     std::uint32_t width,
                     std::uint32_t height) {
    if (mVertices.empty()) {
        return;
    }
    if (mVertices.size() > mVertexCapacity) {
        mVertexCapacity = std::max<std::uint64_t>(kInitialVertexCapacity, mVertices.size() * 2);
        mVertexBuffer =
            gpu::createBuffer(mDevice, wgpu::BufferUsage::Vertex | wgpu::BufferUsage::CopyDst,
                              mVertexCapacity * sizeof(Vertex), "overlay vertices");
    }
    mQueue.WriteBuffer(mVertexBuffer, 0, mVertices.data(), mVertices.size() * sizeof(Vertex));
    const float viewport[4] = {float(width), float(height), 0.0f, 0.0f};
    mQueue.WriteBuffer(mViewport, 0, viewport, sizeof(viewport));

    wgpu::RenderPassColorAttachment color{};
    color.view = target;
    color.loadOp = wgpu::LoadOp::Load;
    color.storeOp = wgpu::StoreOp::Store;
    wgpu::RenderPassDescriptor descriptor{};
    descriptor.label = "encore overlay";
    descriptor.colorAttachmentCount = 1;
    descriptor.colorAttachments = &color;
    wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&descriptor);
    pass.SetPipeline(mPipeline);
    pass.SetBindGroup(0, mBindGroup);
    pass.SetVertexBuffer(0, mVertexBuffer);
    pass.Draw(std::uint32_t(mVertices.size()));
    pass.End();
}

}  // namespace encore::view
