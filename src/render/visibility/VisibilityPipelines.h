#pragma once

// The visibility strategy's model-independent GPU objects (docs/visibility.md): bind group
// layouts, compute and render pipelines, the frame-only bind group and the counters' initial
// values. They depend only on the renderer's setup (device, shader library, layouts, formats,
// sample count, frame uniforms), so a renderer that prepares scene after scene (encore batch,
// RendererOptions::keepPipelines) creates them once (KeptStrategyObjects) instead of compiling
// some twenty pipelines per model.

#include <webgpu/webgpu_cpp.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "encore/core/Result.h"
#include "render/RenderSetup.h"

namespace encore::render {

// visibility_params.wgsl's VisibilityParams, one per view at a 256-byte stride.
struct VisibilityViewParams {
    std::uint32_t itemCount = 0;
    std::uint32_t targetWidth = 0;
    std::uint32_t viewportX = 0;
    std::uint32_t viewportY = 0;
    std::uint32_t viewportWidth = 0;
    std::uint32_t viewportHeight = 0;
    float maxComputePixels = 0.0f;
    std::uint32_t frustumTest = 0;
    std::uint32_t hardwareCapacity = 0;
    // The binning's first bin: each dispatch lists VisibilityTarget::kRoundBins from it.
    std::uint32_t firstBin = 0;
    float maxWorkgroupPixels = 0.0f;
    std::uint32_t samples = 1;
    // The workgroup list: blocks in its first workgroupBlocks entries, then workgroupRecords
    // triangle records of kWorkgroupRecordEntries entries (visibility_raster.wgsl).
    std::uint32_t workgroupBlocks = 0;
    std::uint32_t workgroupRecords = 0;
    // 1: no triangle goes to the hardware pass (visibility_raster.wgsl's workgroupMain clips).
    std::uint32_t computeTakesAll = 0;
};
static_assert(sizeof(VisibilityViewParams) == 60);

struct VisibilityPipelines {
    // Bytes of visibility_counters.wgsl's Counters.
    static constexpr std::uint64_t kCounterBytes = 64;
    // The pipelines create() makes (counted in RenderSetup::pipelinesCreated) for a setup of
    // `sampleCount` samples: the shading ones only where a renderer keeps them (`kept`,
    // RenderSetup::keptObjects: those of multi-view frames, and at one sample their composed
    // variants too). The binning's composed variant at one sample.
    static constexpr std::uint64_t kRenderPipelineCount = 4;
    static constexpr std::uint64_t kShadingVariants = 8;  // Textured, tangent, extensions.
    static constexpr std::uint64_t createdPipelines(std::uint32_t sampleCount, bool kept) {
        const std::uint64_t composed = sampleCount == 1 ? 1 : 0;
        // Clear 1, spheres 1, culling 3, raster 2, binning 1 (+ composed), composition 1.
        const std::uint64_t compute = 9 + composed;
        return compute + kRenderPipelineCount + (kept ? kShadingVariants * (1 + composed) : 0);
    }

    // Fails only where an embedded shader does not compile (a bug, not an input error).
    static Result<std::unique_ptr<VisibilityPipelines>> create(const RenderSetup& setup);

    // The shading pipeline of a bin kind, made on first use unless create() made it (counted in
    // setup.pipelinesCreated); null only where its shader does not compile (a bug). `slots`:
    // for frames of several views, whose parameters and frame uniform each pixel copies from
    // its view's slot (VIEW_SLOTS); frames of one view read them from their bindings, which on
    // the H100 took the shading of a fly-through frame from 0.181 to 0.155 ms (the copies'
    // registers). A renderer that keeps its pipelines (encore batch) draws frames of one view
    // with the slots' pipelines too, so that it never compiles while drawing.
    // `composed`: at one sample, for frames composed in compute, writing the composed frame
    // (visibility_composed.wgsl) rather than the shaded texture.
    const wgpu::ComputePipeline& shading(const RenderSetup& setup,
                                         bool slots,
                                         bool textured,
                                         bool tangent,
                                         bool extensions,
                                         bool composed);

    wgpu::BindGroupLayout frameOnlyLayout;
    wgpu::BindGroupLayout clearLayout;
    wgpu::BindGroupLayout cullLayout;
    wgpu::BindGroupLayout rasterLayout;
    wgpu::BindGroupLayout hardwareLayout;
    wgpu::BindGroupLayout binLayout;
    wgpu::BindGroupLayout binComposedLayout;  // With the composed frame (one sample).
    wgpu::BindGroupLayout shadeLayout;
    wgpu::BindGroupLayout shadeComposedLayout;
    wgpu::BindGroupLayout compositeLayout;
    wgpu::BindGroupLayout composeLayout;
    // The visibility buffer cleared in the frame's first compute pass (visibility_clear.wgsl).
    wgpu::ComputePipeline clear;
    wgpu::ComputePipeline worldSpheres;  // Each item's world sphere (visibility_cull.wgsl).
    wgpu::ComputePipeline cullFirst;
    wgpu::ComputePipeline beginSecondPhase;
    wgpu::ComputePipeline cullSecond;
    wgpu::ComputePipeline raster;
    wgpu::ComputePipeline workgroupRaster;
    wgpu::RenderPipeline hardware;
    wgpu::ComputePipeline binTiles;
    // At one sample, for frames composed in compute: uncovered pixels take the background.
    wgpu::ComputePipeline binTilesComposed;
    // [composed][slots][textured][tangent][extensions] (shading()): without MATERIAL_EXTENSIONS
    // for materials that use none (MaterialResources::shadesExtensions), which bind their base
    // slots only: fewer registers, on the H100 a quarter off the shading pass.
    template <typename T>
    using Pair = std::array<T, 2>;
    Pair<Pair<Pair<Pair<Pair<wgpu::ComputePipeline>>>>> shade;
    bool keptShading = false;  // create() made the slots' shading pipelines.
    // Per sample, writing each sample's depth; compositePixels per pixel without depth, for
    // frames that draw nothing after it (visibility_composite.wgsl); compositeResolved the same
    // at one sample, for passes drawn into the resolved texture (FramePasses::composesResolved).
    wgpu::RenderPipeline composite;
    wgpu::RenderPipeline compositePixels;
    wgpu::RenderPipeline compositeResolved;
    // compositePixels in compute, over every pixel, into a buffer of the target's texels
    // (FramePasses::composeFrame).
    wgpu::ComputePipeline compose;
    // The frame uniform alone (frame.wgsl's group 0) for the raster passes.
    wgpu::BindGroup frameOnlyGroup;
    // Unit count 0, hardware draw (0 vertices, 1 instance, 0, 0): copied over the counters
    // before each view.
    wgpu::Buffer initialCounters;
};

}  // namespace encore::render
