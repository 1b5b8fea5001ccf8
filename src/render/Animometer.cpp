#include "render/Animometer.h"

#include <cstring>
#include <random>

#include "gpu/BindingResource.h"
#include "gpu/LayoutEntry.h"
#include "gpu/Readback.h"
#include "gpu/TimedSubmit.h"
#include "gpu/Upload.h"
#include "render/BundleRecorder.h"

namespace encore::render {

namespace {

// WebGPU's largest allowed minUniformBufferOffsetAlignment, so every device accepts these
// offsets, whether in bind group entries or as dynamic offsets.
constexpr std::uint64_t kSlotSize = 256;

// Mirrors `Triangle` in animometer.wgsl (20 bytes), padded so the binding is a round 32.
struct TriangleParameters {
    float scale;
    float offsetX;
    float offsetY;
    float scalar;
    float scalarOffset;
    float padding[3];
};
static_assert(sizeof(TriangleParameters) == 32);

// The sample's triangle, centred on the origin; the shader scales it by 0.2 .. 0.4.
constexpr float kCorners[] = {0.0f, 0.1f, -0.1f, -0.1f, 0.1f, -0.1f};

// Floats in [0, 1) from the top 24 bits of mt19937, whose output (unlike
// std::uniform_real_distribution's) is the same with every standard library.
class UnitRandom {
  public:
    explicit UnitRandom(std::uint32_t seed) : mEngine(seed) {}
    float next() { return float(mEngine() >> 8) * (1.0f / 16777216.0f); }

  private:
    std::mt19937 mEngine;
};

// The ranges of the WebGPU sample: triangles 2-4 % of the screen wide, centred within 90 % of
// it, spinning at 0.5 .. 2 half-turns per ten seconds from a random phase.
TriangleParameters randomTriangle(UnitRandom& random) {
    TriangleParameters triangle{};
    triangle.scale = random.next() * 0.2f + 0.2f;
    triangle.offsetX = 0.9f * (random.next() * 2.0f - 1.0f);
    triangle.offsetY = 0.9f * (random.next() * 2.0f - 1.0f);
    triangle.scalar = random.next() * 1.5f + 0.5f;
    triangle.scalarOffset = random.next() * 10.0f;
    return triangle;
}

wgpu::RenderPipeline createPipeline(const wgpu::Device& device,
                                    const wgpu::ShaderModule& module,
                                    const wgpu::PipelineLayout& layout) {
    wgpu::VertexAttribute corner{};
    corner.format = wgpu::VertexFormat::Float32x2;
    corner.offset = 0;
    corner.shaderLocation = 0;
    wgpu::VertexBufferLayout vertexLayout{};
    vertexLayout.arrayStride = 2 * sizeof(float);
    vertexLayout.attributeCount = 1;
    vertexLayout.attributes = &corner;

    wgpu::ColorTargetState target{};
    target.format = RenderTarget::kColorFormat;
    wgpu::FragmentState fragment{};
    fragment.module = module;
    fragment.entryPoint = "fragmentMain";
    fragment.targetCount = 1;
    fragment.targets = &target;

    // The target always has depth; the triangles ignore it (later draws simply cover earlier
    // ones, as in the sample), but the pipeline and bundle must match the pass's attachments.
    wgpu::DepthStencilState depth{};
    depth.format = RenderTarget::kDepthFormat;
    depth.depthWriteEnabled = wgpu::OptionalBool::False;
    depth.depthCompare = wgpu::CompareFunction::Always;

    wgpu::RenderPipelineDescriptor descriptor{};
    descriptor.label = "animometer";
    descriptor.layout = layout;
    descriptor.vertex.module = module;
    descriptor.vertex.entryPoint = "vertexMain";
    descriptor.vertex.bufferCount = 1;
    descriptor.vertex.buffers = &vertexLayout;
    descriptor.primitive.topology = wgpu::PrimitiveTopology::TriangleList;
    descriptor.primitive.cullMode = wgpu::CullMode::None;
    descriptor.depthStencil = &depth;
    descriptor.multisample.count = 1;
    descriptor.fragment = &fragment;
    return device.CreateRenderPipeline(&descriptor);
}

}  // namespace

Result<AnimometerScene> AnimometerScene::create(gpu::Context& context,
                                                shaders::ShaderLibrary& shaders,
                                                const AnimometerOptions& options) {
    if (options.triangles == 0 || options.triangles > kMaxAnimometerTriangles) {
        return makeError(ErrorCode::InvalidArgument,
                         "The animometer draws 1 to " + std::to_string(kMaxAnimometerTriangles) +
                             " triangles (got " + std::to_string(options.triangles) + ").");
    }
    // One driver memory mapping per bind group, or per dynamic-offset bind while the pass runs.
    if (const auto budget = context.mappingBudget(); budget && options.triangles > *budget) {
        return makeError(ErrorCode::Unsupported,
                         "The animometer's " + std::to_string(options.triangles) +
                             " triangles need as many bind groups (or dynamic-offset binds); this "
                             "driver (lavapipe) maps memory for each and would crash at the "
                             "kernel's limit (room for " +
                             std::to_string(*budget) +
                             "; raise it with sysctl -w vm.max_map_count=262144).");
    }
    const wgpu::Device& device = context.device();
    wgpu::Limits limits{};
    device.GetLimits(&limits);
    const std::uint64_t parameterBytes = std::uint64_t(options.triangles) * kSlotSize;
    if (parameterBytes > limits.maxBufferSize) {
        return makeError(ErrorCode::LimitExceeded,
                         "The animometer's parameter buffer for " +
                             std::to_string(options.triangles) + " triangles (" +
                             std::to_string(parameterBytes) +
                             " bytes) exceeds the device's maxBufferSize (" +
                             std::to_string(limits.maxBufferSize) + " bytes).");
    }

    AnimometerScene scene;
    scene.mContext = &context;
    scene.mOptions = options;
    auto target = RenderTarget::create(device, {options.width, options.height, 1, false});
    if (!target) {
        return target.error().withContext("Creating the animometer");
    }
    scene.mTarget = std::move(*target);

    ENCORE_TRY_ASSIGN(auto module, shaders.module("animometer.wgsl"));
    const auto uniform = gpu::LayoutEntry::uniform(0, wgpu::ShaderStage::Vertex);
    const wgpu::BindGroupLayout timeLayout =
        gpu::makeBindGroupLayout(device, {uniform}, "animometer time");
    const wgpu::BindGroupLayout triangleLayout = gpu::makeBindGroupLayout(
        device, {options.dynamicOffsets ? uniform.withDynamicOffset() : uniform},
        "animometer triangle");
    scene.mPipeline = createPipeline(device, module,
                                     gpu::makePipelineLayout(device, {timeLayout, triangleLayout}));

    scene.mVertices = gpu::createBufferFrom(device, wgpu::BufferUsage::Vertex,
                                            std::span<const float>(kCorners), "animometer corners");
    // 16 bytes: the time is one f32, padded to the uniform alignment.
    scene.mTime = gpu::createBuffer(device, wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst,
                                    16, "animometer time");
    scene.mTimeGroup = gpu::makeBindGroup(device, timeLayout, {{0, scene.mTime, 0, 16}});

    // Written straight into the mapped buffer: at a million triangles a staging copy would be
    // another 256 MB.
    wgpu::BufferDescriptor parameters{};
    parameters.label = "animometer triangles";
    parameters.size = parameterBytes;
    parameters.usage = wgpu::BufferUsage::Uniform;
    parameters.mappedAtCreation = true;
    scene.mTriangles = device.CreateBuffer(&parameters);
    auto* mapped = static_cast<std::uint8_t*>(scene.mTriangles.GetMappedRange(0, parameterBytes));
    if (!mapped) {
        return makeError(ErrorCode::DeviceError,
                         "Could not map the animometer's parameter buffer (" +
                             std::to_string(parameterBytes) + " bytes).");
    }
    std::memset(mapped, 0, parameterBytes);
    UnitRandom random(options.seed);
    for (std::uint32_t i = 0; i < options.triangles; ++i) {
        const TriangleParameters triangle = randomTriangle(random);
        std::memcpy(mapped + i * kSlotSize, &triangle, sizeof(triangle));
    }
    scene.mTriangles.Unmap();

    if (options.dynamicOffsets) {
        scene.mTriangleGroups.push_back(gpu::makeBindGroup(
            device, triangleLayout, {{0, scene.mTriangles, 0, sizeof(TriangleParameters)}}));
    } else {
        scene.mTriangleGroups.reserve(options.triangles);
        for (std::uint32_t i = 0; i < options.triangles; ++i) {
            scene.mTriangleGroups.push_back(gpu::makeBindGroup(
                device, triangleLayout,
                {{0, scene.mTriangles, i * kSlotSize, sizeof(TriangleParameters)}}));
        }
    }

    if (options.bundle) {
        RenderSetup setup;
        setup.device = device;
        setup.queue = context.queue();
        setup.colorFormat = RenderTarget::kColorFormat;
        setup.depthFormat = RenderTarget::kDepthFormat;
        setup.sampleCount = 1;
        RecordedBundle recorded = recordBundle(
            setup, "animometer", [&](RenderEncoder& encoder) { scene.recordDraws(encoder); });
        scene.mBundle = std::move(recorded.bundle);
        scene.mBundleContents = recorded.contents;
    }
    ENCORE_TRY(context.checkNoErrors("Creating " + scene.describe()));
    return scene;
}

void AnimometerScene::recordDraws(RenderEncoder& encoder) const {
    encoder.setPipeline(mPipeline);
    encoder.setBindGroup(0, mTimeGroup);
    encoder.setVertexBuffer(0, mVertices);
    if (mOptions.dynamicOffsets) {
        const wgpu::BindGroup& group = mTriangleGroups.front();
        for (std::uint32_t i = 0; i < mOptions.triangles; ++i) {
            encoder.setBindGroup(1, group, std::uint32_t(i * kSlotSize));
            encoder.draw(3, 1, 0, 0, scene::Topology::TriangleList);
        }
    } else {
        for (const wgpu::BindGroup& group : mTriangleGroups) {
            encoder.setBindGroup(1, group);
            encoder.draw(3, 1, 0, 0, scene::Topology::TriangleList);
        }
    }
}

FrameTiming AnimometerScene::renderFrame(float timeSeconds, gpu::GpuTimer* timer) {
    mFrameCounters = {};
    mContext->queue().WriteBuffer(mTime, 0, &timeSeconds, sizeof(timeSeconds));
    const gpu::SubmitTiming timing =
        gpu::submitTimed(*mContext, timer, [&](const wgpu::CommandEncoder& commands) {
            wgpu::RenderPassColorAttachment color = mTarget.colorAttachment(kClearColor);
            wgpu::RenderPassDepthStencilAttachment depth = mTarget.depthAttachment();
            wgpu::RenderPassDescriptor passDescriptor{};
            passDescriptor.label = "animometer frame";
            passDescriptor.colorAttachmentCount = 1;
            passDescriptor.colorAttachments = &color;
            passDescriptor.depthStencilAttachment = &depth;
            passDescriptor.timestampWrites = timer ? timer->nextPass("animometer") : nullptr;
            wgpu::RenderPassEncoder pass = commands.BeginRenderPass(&passDescriptor);
            RenderEncoder encoder(pass, mFrameCounters);
            if (mBundle) {
                encoder.executeBundles(std::span(&mBundle, 1));
            } else {
                recordDraws(encoder);
            }
            pass.End();
        });
    return {timing.encodeMilliseconds, timing.submitMilliseconds, timing.gpuMilliseconds};
}

Result<void> AnimometerScene::resize(std::uint32_t width, std::uint32_t height) {
    RenderTargetOptions options = mTarget.options();
    options.width = width;
    options.height = height;
    ENCORE_TRY_ASSIGN(mTarget, RenderTarget::create(mContext->device(), options));
    mOptions.width = width;
    mOptions.height = height;
    return {};
}

Result<image::ImageRgba8> AnimometerScene::readImage() {
    ENCORE_TRY_ASSIGN(auto image, gpu::readTexture(*mContext, mTarget.colorTexture()));
    ENCORE_TRY(mContext->checkNoErrors("Rendering " + describe()));
    return image;
}

std::string AnimometerScene::describe() const {
    return "animometer " + std::to_string(mOptions.triangles) + " triangles, " +
           (mOptions.dynamicOffsets ? "dynamic offsets" : "bind groups") + ", " +
           (mOptions.bundle ? "bundle" : "direct");
}

}  // namespace encore::render
