#include "render/visibility/VisibilityPipelines.h"

#include <deque>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "encore/gpu/Context.h"
#include "encore/render/RenderTarget.h"
#include "gpu/BindingResource.h"
#include "gpu/FullscreenPipeline.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Upload.h"
#include "render/culling/CullingUniform.h"
#include "render/visibility/MaterialBins.h"
#include "render/visibility/VisibilityTarget.h"

namespace encore::render {

namespace {

constexpr auto kCompute = wgpu::ShaderStage::Compute;
// The start of a bin's record (visibility_bin_record.wgsl), as visibility_shade.wgsl reads it.
constexpr std::uint64_t kBinUniformBytes = 16;

// A compute pipeline of `entryPoint` over `groups`, labelled with the entry point.
wgpu::ComputePipelineDescriptor computeDescriptor(
    const wgpu::Device& device,
    const wgpu::ShaderModule& module,
    const char* entryPoint,
    std::initializer_list<wgpu::BindGroupLayout> groups) {
    wgpu::ComputePipelineDescriptor descriptor{};
    descriptor.label = entryPoint;
    descriptor.layout = gpu::makePipelineLayout(device, groups);
    descriptor.compute.module = module;
    descriptor.compute.entryPoint = entryPoint;
    return descriptor;
}

// computeDescriptor's pipeline, made on this thread.
wgpu::ComputePipeline computePipeline(const wgpu::Device& device,
                                      const wgpu::ShaderModule& module,
                                      const char* entryPoint,
                                      std::initializer_list<wgpu::BindGroupLayout> groups) {
    const wgpu::ComputePipelineDescriptor descriptor =
        computeDescriptor(device, module, entryPoint, groups);
    return device.CreateComputePipeline(&descriptor);
}

// visibility_composite.wgsl's flags for the target's sample count.
std::set<std::string, std::less<>> compositeFlags(const RenderSetup& setup) {
    std::set<std::string, std::less<>> flags;
    if (setup.sampleCount > 1) {
        flags.insert("MULTISAMPLED");
    }
    return flags;
}

// The shaders that write the frame composed in compute (visibility_composed.wgsl).
std::set<std::string, std::less<>> composedFlags(const RenderSetup& setup) {
    std::set<std::string, std::less<>> flags = {"COMPOSED"};
    if (setup.colorFormat == wgpu::TextureFormat::RGBA16Float) {
        flags.insert("HALF_OUTPUT");
    }
    return flags;
}

// The shading shader of a bin kind (VisibilityPipelines::shading): one pipeline serves every
// material of its kind.
Result<wgpu::ShaderModule> shadingModule(const RenderSetup& setup,
                                         bool slots,
                                         bool textured,
                                         bool tangent,
                                         bool extensions,
                                         bool composed) {
    std::set<std::string, std::less<>> flags = {"SAMPLE_GRADIENT"};
    if (composed) {
        flags.merge(composedFlags(setup));
    }
    if (slots) {
        flags.insert("VIEW_SLOTS");
    }
    if (extensions) {
        flags.insert("MATERIAL_EXTENSIONS");
    }
    if (textured) {
        flags.insert("MATERIAL_TEXTURES");
        flags.insert("SAMPLER_PALETTE");
    }
    if (tangent) {
        flags.insert("HAS_TANGENT");
    }
    return setup.shaders->module("visibility_shade.wgsl", flags);
}

// MaterialResources::drawBindGroup's layouts.
const wgpu::BindGroupLayout& shadingMaterialLayout(const RenderSetup& setup,
                                                   bool textured,
                                                   bool extensions) {
    return !textured    ? setup.layouts->materialUniformOnly
           : extensions ? setup.layouts->material
                        : setup.layouts->materialBase;
}

// Compute pipelines created side by side: Dawn compiles asynchronous pipelines on its worker
// threads, so the four variants of the PBR shading shader, the bulk of the strategy's start in
// a batch, no longer compile one after another.
class AsyncComputePipelines {
  public:
    explicit AsyncComputePipelines(const RenderSetup& setup) : mSetup(setup) {}
    // An early return (a shader that failed to build) still waits: the callbacks write here.
    ~AsyncComputePipelines() {
        if (!mWaited) {
            (void)wait();
        }
    }
    AsyncComputePipelines(const AsyncComputePipelines&) = delete;
    AsyncComputePipelines& operator=(const AsyncComputePipelines&) = delete;

    // Starts creating `target`, set when wait() returns.
    void add(wgpu::ComputePipeline& target,
             const wgpu::ShaderModule& module,
             const char* entryPoint,
             std::initializer_list<wgpu::BindGroupLayout> groups) {
        const wgpu::ComputePipelineDescriptor descriptor =
            computeDescriptor(mSetup.device, module, entryPoint, groups);
        auto& failure = mFailures.emplace_back();
        mFutures.push_back(mSetup.device.CreateComputePipelineAsync(
            &descriptor, wgpu::CallbackMode::WaitAnyOnly,
            [&target, &failure, entryPoint](wgpu::CreatePipelineAsyncStatus status,
                                            wgpu::ComputePipeline pipeline,
                                            wgpu::StringView message) {
                if (status == wgpu::CreatePipelineAsyncStatus::Success) {
                    target = std::move(pipeline);
                } else {
                    failure = std::string(entryPoint) + ": " + std::string(message);
                }
            }));
    }

    // Waits for every pipeline; an error names the first that failed (a bug: the shaders are
    // embedded).
    Result<void> wait() {
        // Every future, even after one failed: no callback may outlive this object.
        mWaited = true;
        bool waited = true;
        for (const wgpu::Future& future : mFutures) {
            waited = mSetup.context->wait(future) && waited;
        }
        if (!waited) {
            return makeError(ErrorCode::DeviceError,
                             "Waiting for the visibility strategy's pipelines failed.");
        }
        for (const std::string& failure : mFailures) {
            if (!failure.empty()) {
                return makeError(ErrorCode::ValidationError,
                                 "A visibility pipeline could not be created: " + failure);
            }
        }
        return {};
    }

  private:
    const RenderSetup& mSetup;
    std::vector<wgpu::Future> mFutures;
    std::deque<std::string> mFailures;  // Stable addresses for the callbacks.
    bool mWaited = false;
};

void createLayouts(const wgpu::Device& device,
                   wgpu::TextureFormat colorFormat,
                   VisibilityPipelines& p) {
    using gpu::LayoutEntry;
    const auto vertex = wgpu::ShaderStage::Vertex;
    const auto fragment = wgpu::ShaderStage::Fragment;
    const auto params =
        LayoutEntry::uniform(0, kCompute, sizeof(VisibilityViewParams)).withDynamicOffset();
    // The frame uniform alone (frame.wgsl's group 0) for the raster passes: the frame layout's
    // lights would take one of the eight storage buffers a stage may bind.
    p.frameOnlyLayout = gpu::makeBindGroupLayout(
        device, {LayoutEntry::uniform(0, kCompute | vertex | fragment, sizeof(FrameUniform))},
        "visibility frame");
    p.clearLayout =
        gpu::makeBindGroupLayout(device, {LayoutEntry::storage(0, kCompute)}, "visibility clear");
    p.cullLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(2, kCompute),
         LayoutEntry::readOnlyStorage(3, kCompute), LayoutEntry::storage(4, kCompute),
         LayoutEntry::storage(5, kCompute),
         LayoutEntry::uniform(10, kCompute, sizeof(CullingUniform)),
         LayoutEntry::storage(11, kCompute),
         LayoutEntry::texture(12, kCompute, wgpu::TextureSampleType::UnfilterableFloat),
         LayoutEntry::storage(13, kCompute)},
        "visibility culling");
    p.rasterLayout = gpu::makeBindGroupLayout(
        device,
        {params, LayoutEntry::readOnlyStorage(1, kCompute),
         LayoutEntry::readOnlyStorage(2, kCompute), LayoutEntry::readOnlyStorage(3, kCompute),
         LayoutEntry::storage(4, kCompute), LayoutEntry::storage(5, kCompute),
         LayoutEntry::storage(6, kCompute), LayoutEntry::storage(7, kCompute),
         LayoutEntry::storage(9, kCompute),
         LayoutEntry::uniform(10, kCompute, sizeof(CullingUniform)),
         LayoutEntry::texture(12, kCompute, wgpu::TextureSampleType::UnfilterableFloat)},
        "visibility raster");
    p.hardwareLayout = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::uniform(0, vertex | fragment, sizeof(VisibilityViewParams))
             .withDynamicOffset(),
         LayoutEntry::readOnlyStorage(1, vertex), LayoutEntry::readOnlyStorage(2, vertex),
         LayoutEntry::readOnlyStorage(3, vertex), LayoutEntry::readOnlyStorage(4, vertex),
         LayoutEntry::readOnlyStorage(5, vertex), LayoutEntry::storage(6, fragment)},
        "visibility hardware");
    // The composed frame (the target's scene colour as a storage texture) and its Composition
    // (visibility_composed.wgsl), at `binding` on.
    const wgpu::TextureFormat composedFormat = colorFormat == wgpu::TextureFormat::RGBA16Float
                                                   ? wgpu::TextureFormat::RGBA16Float
                                                   : RenderTarget::kBytesFormat;
    const auto composed = [composedFormat](std::uint32_t binding) {
        return std::array{
            LayoutEntry::storageTexture(binding, kCompute, composedFormat),
            LayoutEntry::uniform(binding + 1, kCompute, VisibilityTarget::kCompositionBytes)};
    };
    std::vector<LayoutEntry> bins = {params,
                                     LayoutEntry::readOnlyStorage(1, kCompute),
                                     LayoutEntry::readOnlyStorage(2, kCompute),
                                     LayoutEntry::readOnlyStorage(3, kCompute),
                                     LayoutEntry::storage(4, kCompute),
                                     LayoutEntry::storage(5, kCompute)};
    p.binLayout = gpu::makeBindGroupLayout(device, bins, "visibility bins");
    const auto binsComposed = composed(6);
    bins.insert(bins.end(), binsComposed.begin(), binsComposed.end());
    p.binComposedLayout = gpu::makeBindGroupLayout(device, bins, "visibility bins, composed");
    // The shading pass reads the slots of a group of views (VisibilityTarget); the bin's record
    // as a uniform, which leaves the composed frame one of the eight storage buffers.
    std::vector<LayoutEntry> shade = {
        LayoutEntry::uniform(0, kCompute, VisibilityTarget::kSlotBindingBytes).withDynamicOffset(),
        LayoutEntry::readOnlyStorage(1, kCompute),
        LayoutEntry::readOnlyStorage(2, kCompute),
        LayoutEntry::readOnlyStorage(3, kCompute),
        LayoutEntry::readOnlyStorage(4, kCompute),
        LayoutEntry::readOnlyStorage(5, kCompute),
        LayoutEntry::readOnlyStorage(6, kCompute),
        LayoutEntry::uniform(7, kCompute, kBinUniformBytes).withDynamicOffset(),
        LayoutEntry::uniform(10, kCompute, MaterialBins::kBlockBytes).withDynamicOffset()};
    std::vector<LayoutEntry> shadeComposed = shade;
    shade.push_back(LayoutEntry::storageTexture(8, kCompute, wgpu::TextureFormat::RGBA16Float,
                                                wgpu::StorageTextureAccess::WriteOnly,
                                                wgpu::TextureViewDimension::e2DArray));
    p.shadeLayout = gpu::makeBindGroupLayout(device, shade, "visibility shading");
    const auto shadingComposed = composed(8);
    shadeComposed.insert(shadeComposed.end(), shadingComposed.begin(), shadingComposed.end());
    p.shadeComposedLayout =
        gpu::makeBindGroupLayout(device, shadeComposed, "visibility shading, composed");
    p.compositeLayout = gpu::makeBindGroupLayout(
        device,
        {LayoutEntry::readOnlyStorage(0, fragment),
         LayoutEntry::texture(1, fragment, wgpu::TextureSampleType::UnfilterableFloat,
                              wgpu::TextureViewDimension::e2DArray)},
        "visibility composite");
    std::vector<LayoutEntry> compose = {
        LayoutEntry::readOnlyStorage(0, kCompute),
        LayoutEntry::texture(1, kCompute, wgpu::TextureSampleType::UnfilterableFloat,
                             wgpu::TextureViewDimension::e2DArray)};
    const auto composeComposed = composed(2);
    compose.insert(compose.end(), composeComposed.begin(), composeComposed.end());
    p.composeLayout = gpu::makeBindGroupLayout(device, compose, "visibility composition");
}

Result<wgpu::RenderPipeline> hardwarePipeline(const RenderSetup& setup,
                                              const VisibilityPipelines& p) {
    const wgpu::Device& device = setup.device;
    ENCORE_TRY_ASSIGN(auto hardware, setup.shaders->module("visibility_hardware.wgsl"));
    wgpu::DepthStencilState depth{};
    depth.format = wgpu::TextureFormat::Depth32Float;
    // No depth test: the fragment shader writes storage, so Vulkan tests depth only after it
    // has run (the atomic happens either way), and the attachment, never written, is neither
    // cleared nor stored per view (VisibilityStrategy::encodeHardwareRaster).
    depth.depthWriteEnabled = wgpu::OptionalBool::False;
    depth.depthCompare = wgpu::CompareFunction::Always;
    wgpu::FragmentState fragment{};
    fragment.module = hardware;
    fragment.entryPoint = "fragmentMain";
    wgpu::RenderPipelineDescriptor pipeline{};
    pipeline.label = "visibility hardware";
    pipeline.layout = gpu::makePipelineLayout(device, {p.frameOnlyLayout, p.hardwareLayout});
    pipeline.vertex.module = hardware;
    pipeline.vertex.entryPoint = "vertexMain";
    pipeline.primitive.topology = wgpu::PrimitiveTopology::TriangleList;
    pipeline.primitive.cullMode = wgpu::CullMode::None;  // Back faces were culled in compute.
    pipeline.depthStencil = &depth;
    pipeline.multisample.count = setup.sampleCount;
    pipeline.fragment = &fragment;
    return device.CreateRenderPipeline(&pipeline);
}

// Per sample (with depth), or per pixel (blended, no depth) into the target's samples or, with
// `resolved`, into its resolved texture (one sample, no depth attachment).
Result<wgpu::RenderPipeline> compositePipeline(const RenderSetup& setup,
                                               const VisibilityPipelines& p,
                                               bool perPixel,
                                               bool resolved = false) {
    ENCORE_TRY_ASSIGN(auto composite,
                      setup.shaders->module("visibility_composite.wgsl", compositeFlags(setup)));
    gpu::FullscreenPipelineDescriptor descriptor;
    descriptor.label = "visibility composite";
    descriptor.module = composite;
    descriptor.fragmentEntryPoint = perPixel ? "pixelMain" : "fragmentMain";
    descriptor.layout = gpu::makePipelineLayout(setup.device, {p.compositeLayout});
    descriptor.colorFormat = setup.colorFormat;
    descriptor.depthFormat = resolved ? wgpu::TextureFormat::Undefined : setup.depthFormat;
    descriptor.writesDepth = !perPixel;
    if (perPixel) {
        // Premultiplied over the background (visibility_composite.wgsl's pixelMain).
        wgpu::BlendComponent over{};
        over.srcFactor = wgpu::BlendFactor::One;
        over.dstFactor = wgpu::BlendFactor::OneMinusSrcAlpha;
        descriptor.blend = wgpu::BlendState{over, over};
    }
    descriptor.sampleCount = resolved ? 1 : setup.sampleCount;
    return gpu::makeFullscreenPipeline(setup.device, descriptor);
}

}  // namespace

Result<std::unique_ptr<VisibilityPipelines>> VisibilityPipelines::create(const RenderSetup& setup) {
    auto created = std::make_unique<VisibilityPipelines>();
    VisibilityPipelines& p = *created;
    const wgpu::Device& device = setup.device;
    createLayouts(device, setup.colorFormat, p);

    shaders::ShaderLibrary& library = *setup.shaders;
    // Side by side where a renderer keeps them for scene after scene (encore batch, whose start
    // they were); one after another where each prepare makes its own, which then keeps Dawn's
    // worker threads and their memory out of every prepare (on lavapipe, a process preparing
    // every strategy over and over held 35 MiB more resident memory, and less steadily), and in
    // setups made outside a Renderer, which have no context to wait with.
    std::optional<AsyncComputePipelines> async;
    if (setup.context && setup.keptObjects) {
        async.emplace(setup);
    }
    std::uint64_t made = 0;
    auto add = [&](wgpu::ComputePipeline& target, const wgpu::ShaderModule& module,
                   const char* entryPoint, std::initializer_list<wgpu::BindGroupLayout> groups) {
        ++made;
        if (async) {
            async->add(target, module, entryPoint, groups);
        } else {
            target = computePipeline(device, module, entryPoint, groups);
        }
    };
    // The shading pipelines first: they take longest. Where every prepare makes its own, they
    // are made on first use (shading()): only the bin kinds and view mode a scene draws. At one
    // sample, frames composed in compute shade into the composed frame (composed variants).
    if (async) {
        for (bool composed : {false, true}) {
            if (composed && setup.sampleCount != 1) {
                continue;
            }
            for (bool textured : {false, true}) {
                for (bool tangent : {false, true}) {
                    for (bool extensions : {false, true}) {
                        ENCORE_TRY_ASSIGN(auto shade, shadingModule(setup, true, textured, tangent,
                                                                    extensions, composed));
                        add(p.shade[composed][1][textured][tangent][extensions], shade, "shadeMain",
                            {setup.layouts->frame, composed ? p.shadeComposedLayout : p.shadeLayout,
                             shadingMaterialLayout(setup, textured, extensions)});
                    }
                }
            }
        }
        p.keptShading = true;
    }
    ENCORE_TRY_ASSIGN(auto clear, library.module("visibility_clear.wgsl"));
    add(p.clear, clear, "clearMain", {p.clearLayout});
    ENCORE_TRY_ASSIGN(auto cull, library.module("visibility_cull.wgsl"));
    const auto cullGroups = {p.frameOnlyLayout, p.cullLayout};
    add(p.worldSpheres, cull, "worldSphereMain", cullGroups);
    add(p.cullFirst, cull, "cullFirstPhase", cullGroups);
    add(p.beginSecondPhase, cull, "beginSecondPhase", cullGroups);
    add(p.cullSecond, cull, "cullSecondPhase", cullGroups);
    ENCORE_TRY_ASSIGN(auto raster, library.module("visibility_raster.wgsl"));
    add(p.raster, raster, "rasterMain", {p.frameOnlyLayout, p.rasterLayout});
    add(p.workgroupRaster, raster, "workgroupMain", {p.frameOnlyLayout, p.rasterLayout});
    p.frameOnlyGroup = gpu::makeBindGroup(device, p.frameOnlyLayout,
                                          {{0, setup.frame->buffer(), 0, sizeof(FrameUniform)}},
                                          "visibility frame");

    ENCORE_TRY_ASSIGN(auto bins, library.module("visibility_bins.wgsl"));
    add(p.binTiles, bins, "binMain", {p.binLayout});
    if (setup.sampleCount == 1) {
        ENCORE_TRY_ASSIGN(auto binsComposed,
                          library.module("visibility_bins.wgsl", composedFlags(setup)));
        add(p.binTilesComposed, binsComposed, "binMain", {p.binComposedLayout});
    }
    {
        std::set<std::string, std::less<>> flags = compositeFlags(setup);
        flags.merge(composedFlags(setup));  // composeMain writes the composed frame.
        ENCORE_TRY_ASSIGN(auto compose, library.module("visibility_composite.wgsl", flags));
        add(p.compose, compose, "composeMain", {p.composeLayout});
    }
    // The render pipelines meanwhile, on this thread.
    ENCORE_TRY_ASSIGN(p.hardware, hardwarePipeline(setup, p));
    ENCORE_TRY_ASSIGN(p.composite, compositePipeline(setup, p, false));
    ENCORE_TRY_ASSIGN(p.compositePixels, compositePipeline(setup, p, true));
    ENCORE_TRY_ASSIGN(p.compositeResolved, compositePipeline(setup, p, true, true));
    if (async) {
        ENCORE_TRY(async->wait());
    }
    ENCORE_CHECK(made + kRenderPipelineCount == createdPipelines(setup.sampleCount, p.keptShading),
                 "VisibilityPipelines::createdPipelines disagrees with create()");
    setup.pipelinesCreated += made + kRenderPipelineCount;

    std::array<std::uint32_t, kCounterBytes / 4> initial{};
    initial[5] = 1;  // The hardware draw's instance count.
    p.initialCounters = gpu::createBufferFrom<std::uint32_t>(
        device, wgpu::BufferUsage::CopySrc, initial, "visibility initial counters");
    return created;
}

const wgpu::ComputePipeline& VisibilityPipelines::shading(const RenderSetup& setup,
                                                          bool slots,
                                                          bool textured,
                                                          bool tangent,
                                                          bool extensions,
                                                          bool composed) {
    // A renderer that keeps its pipelines made the slots' ones and draws every frame with them.
    slots = slots || keptShading;
    wgpu::ComputePipeline& pipeline = shade[composed][slots][textured][tangent][extensions];
    if (!pipeline) {
        auto module = shadingModule(setup, slots, textured, tangent, extensions, composed);
        if (module.ok()) {
            pipeline =
                computePipeline(setup.device, *module, "shadeMain",
                                {setup.layouts->frame, composed ? shadeComposedLayout : shadeLayout,
                                 shadingMaterialLayout(setup, textured, extensions)});
            ++setup.pipelinesCreated;
        }
    }
    return pipeline;
}

}  // namespace encore::render
