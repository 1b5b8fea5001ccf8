#pragma once

// Every argument of a mesh render pipeline, as a small POD with no padding, so that it can be
// compared and hashed bytewise (the pipeline cache's key, after Filament's
// WebGPUPipelineCache). Strategies without a cache build one per pipeline all the same.

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <string>
#include <type_traits>

#include "encore/core/Result.h"
#include "shaders/ShaderLibrary.h"

namespace encore::render {

struct RenderSetup;

struct VertexAttributeKey {
    wgpu::VertexFormat format = wgpu::VertexFormat::Float32x3;
    std::uint32_t offset = 0;
    std::uint32_t shaderLocation = 0;
};

struct VertexBufferKey {
    static constexpr std::uint32_t kMaxAttributes = 8;
    std::uint32_t arrayStride = 0;
    std::uint32_t attributeCount = 0;
    VertexAttributeKey attributes[kMaxAttributes] = {};
};

struct PipelineKey {
    static constexpr std::uint32_t kMaxBuffers = 8;  // WebGPU's maxVertexBuffers.
    std::uint32_t bufferCount = 0;
    VertexBufferKey buffers[kMaxBuffers] = {};  // Sorted by their first shader location.
    wgpu::PrimitiveTopology topology = wgpu::PrimitiveTopology::TriangleList;
    wgpu::IndexFormat stripIndexFormat = wgpu::IndexFormat::Undefined;
    wgpu::CullMode cullMode = wgpu::CullMode::None;
    wgpu::FrontFace frontFace = wgpu::FrontFace::CCW;
    std::uint32_t blend = 0;  // 1: alpha blending (glTF BLEND), depth writes kept.
    wgpu::TextureFormat colorFormat = wgpu::TextureFormat::Undefined;
    wgpu::TextureFormat depthFormat = wgpu::TextureFormat::Undefined;
    std::uint32_t sampleCount = 1;
    shaders::ShaderVariantKey shader;

    bool operator==(const PipelineKey& other) const;
    // Adds a vertex buffer; attributes are added to the last buffer with addAttribute.
    void addBuffer(std::uint32_t arrayStride);
    void addAttribute(wgpu::VertexFormat format, std::uint32_t offset, std::uint32_t location);
    // Sorts attributes by location within each buffer and buffers by their first location.
    void sortLayouts();
};
static_assert(std::has_unique_object_representations_v<PipelineKey>,
              "PipelineKey must have no padding: it is hashed bytewise");

struct PipelineKeyHash {
    std::size_t operator()(const PipelineKey& key) const noexcept;
};

// The colour targets of a pipeline of `shader`: 1, or with pass targets the colour and the four
// pass images (render/PassTargets.h).
std::uint32_t sceneColorTargets(const shaders::ShaderVariantKey& shader);

// Creates the mesh pipeline a key describes.
Result<wgpu::RenderPipeline> createMeshPipeline(const RenderSetup& setup,
                                                const PipelineKey& key,
                                                const std::string& label);

}  // namespace encore::render
