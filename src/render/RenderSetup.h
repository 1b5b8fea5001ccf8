#pragma once

// What a strategy's pipelines and bind groups must be compatible with (RenderSetup), and where
// Renderer::prepare's time went (PrepareTimes).

#include <webgpu/webgpu_cpp.h>

#include <cstdint>
#include <optional>

#include "encore/gpu/DeviceLimits.h"
#include "encore/render/RendererStats.h"
#include "render/BindGroupLayouts.h"
#include "render/FrameUniforms.h"
#include "shaders/ShaderLibrary.h"

namespace encore::gpu {
class Context;
class ResourcePool;
}  // namespace encore::gpu

namespace encore::render {

class MipmapGenerator;
class KeptStrategyObjects;
class PipelineCache;

// What a strategy's pipelines and bind groups must be compatible with.
struct RenderSetup {
    wgpu::Device device;
    wgpu::Queue queue;
    // The device's context, whose wait() waits for asynchronous pipeline creation
    // (VisibilityPipelines); null in setups made outside a Renderer.
    const gpu::Context* context = nullptr;
    shaders::ShaderLibrary* shaders = nullptr;
    const BindGroupLayouts* layouts = nullptr;
    const FrameUniforms* frame = nullptr;
    wgpu::TextureFormat colorFormat = wgpu::TextureFormat::RGBA8UnormSrgb;
    wgpu::TextureFormat depthFormat = wgpu::TextureFormat::Depth32Float;
    std::uint32_t sampleCount = 1;
    // ShaderVariantKey::passTargets of the mesh pipelines that draw glTF materials (0: none):
    // with pass targets, every scene pass has four more colour targets of colorFormat
    // (RendererOptions::passTargets, render/PassTargets.h).
    std::uint8_t passTargets = 0;
    // gpu::Context::mappingBudget(): strategies that create a buffer and a bind group per node
    // refuse scenes that would exceed it rather than crash the driver.
    std::optional<std::uint64_t> mappingBudget;
    // gpu::Context::limits(): what buffers and textures are sized against.
    gpu::DeviceLimits limits;
    // Render pipelines created through this setup (createMeshPipeline), and the visibility
    // strategy's own (VisibilityPipelines), for stats.
    mutable std::uint64_t pipelinesCreated = 0;
    // The last Renderer::prepare's times; strategies add their parts.
    mutable PrepareTimes prepareTimes;
    // Pipelines that outlive the prepared strategy (RendererOptions::keepPipelines), owned by
    // the Renderer; null: each strategy caches its own.
    PipelineCache* keptPipelines = nullptr;
    // Strategies' scene-independent objects (the visibility strategy's pipelines and
    // target-sized buffers) kept with the pipelines above, owned by the Renderer; null: each
    // strategy makes its own.
    KeptStrategyObjects* keptObjects = nullptr;
    // Fills textures' mip chains, owned by the Renderer so that its pipelines outlive each
    // scene; null: MaterialResources makes one per scene.
    MipmapGenerator* mipmaps = nullptr;
    // Buffers and textures kept from one scene to the next (a batch's lane, gpu/ResourcePool.h):
    // the GPU scene takes its textures, geometry, instance and material buffers from it and gives
    // them back when it is released; null: created for each scene and released with it.
    gpu::ResourcePool* resources = nullptr;
};

}  // namespace encore::render
