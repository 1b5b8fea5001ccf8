#include "encore/render/Renderer.h"

#include <chrono>

#include "encore/gpu/Readback.h"

namespace encore::render {

namespace {
double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}
}  // namespace

Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<Renderer> Renderer::create(gpu::Context& context, const RendererOptions& options) {
    Renderer renderer;
    renderer.mContext = &context;
    renderer.mOptions = options;
    auto target = RenderTarget::create(context.device(), options.target);
    if (!target) {
        return target.error();
    }
    renderer.mTarget = std::move(*target);
    renderer.mShaders = std::make_unique<shaders::ShaderLibrary>(context.device());
    renderer.mLayouts =
        std::make_unique<BindGroupLayouts>(BindGroupLayouts::create(context.device()));
    renderer.mFrame = std::make_unique<FrameUniforms>(context.device(), *renderer.mLayouts);

    renderer.mSetup = std::make_unique<RenderSetup>();
    RenderSetup& setup = *renderer.mSetup;
    setup.device = context.device();
    setup.queue = context.queue();
    setup.shaders = renderer.mShaders.get();
    setup.layouts = renderer.mLayouts.get();
    setup.frame = renderer.mFrame.get();
    setup.colorFormat = RenderTarget::kColorFormat;
    setup.depthFormat = RenderTarget::kDepthFormat;
    setup.sampleCount = options.target.sampleCount;
    setup.mappingBudget = context.mappingBudget();
    ENCORE_TRY(context.checkNoErrors("Creating the renderer"));
    return renderer;
}

Result<void> Renderer::prepare(const scene::SceneData& scene, StrategyKind kind) {
    if (mStrategy) {
        // Dawn frees objects once the GPU is done with them, on a later tick. Let that happen
        // before the next strategy allocates: peak memory stays one strategy's worth, and
        // drivers that map memory per object (lavapipe) stay below the kernel's limit.
        mStrategy.reset();
        mContext->waitForIdle();
        mContext->device().Tick();
    }
    mSetup->pipelinesCreated = 0;
    mSetup->mappingBudget = mContext->mappingBudget();  // What the previous scene left in use.
    auto strategy = createStrategy(kind);
    const std::string what = "Preparing '" + scene.sourcePath.string() + "' for strategy " +
                             std::string(strategyName(kind));
    auto prepared = strategy->prepare(*mSetup, scene);
    if (!prepared) {
        return prepared.error().withContext(what);
    }
    ENCORE_TRY(mContext->checkNoErrors(what));
    mStrategy = std::move(strategy);
    return {};
}

FrameResult Renderer::renderFrame(const Camera& camera, float timeSeconds,
                                  std::vector<RecordedCall>* trace) {
    return renderPasses(std::span(&camera, 1), timeSeconds, trace);
}

FrameResult Renderer::renderViews(std::span<const Camera> cameras, float timeSeconds) {
    return renderPasses(cameras, timeSeconds, nullptr);
}

FrameResult Renderer::renderPasses(std::span<const Camera> cameras, float timeSeconds,
                                   std::vector<RecordedCall>* trace) {
    FrameResult result;
    if (cameras.empty()) {
        return result;
    }
    const bool multiView = cameras.size() > 1;
    if (multiView) {
        mFrame->writeViews(mContext->device(), mContext->queue(), cameras, timeSeconds);
    } else {
        mFrame->update(mContext->queue(), cameras[0], timeSeconds);
    }
    const FrameState state{cameras[0], timeSeconds, mTimer};

    const auto encodeStart = std::chrono::steady_clock::now();
    wgpu::CommandEncoder commandEncoder = mContext->device().CreateCommandEncoder();
    if (mStrategy) {
        mStrategy->beforePass(commandEncoder, state);
    }
    const std::uint32_t viewWidth = mTarget.width() / std::uint32_t(cameras.size());
    for (std::size_t view = 0; view < cameras.size(); ++view) {
        if (multiView) {
            mFrame->selectView(commandEncoder, view);
        }
        wgpu::RenderPassColorAttachment color = mTarget.colorAttachment(mOptions.clearColor);
        wgpu::RenderPassDepthStencilAttachment depth = mTarget.depthAttachment();
        if (view > 0) {
            color.loadOp = wgpu::LoadOp::Load;  // Keep the views drawn before.
        }
        if (multiView) {
            color.storeOp = wgpu::StoreOp::Store;  // Multisampled contents survive the passes.
        }
        wgpu::RenderPassDescriptor passDescriptor{};
        passDescriptor.label = "encore frame";
        passDescriptor.colorAttachmentCount = 1;
        passDescriptor.colorAttachments = &color;
        passDescriptor.depthStencilAttachment = &depth;
        passDescriptor.timestampWrites = mTimer ? mTimer->nextPass() : nullptr;
        wgpu::RenderPassEncoder pass = commandEncoder.BeginRenderPass(&passDescriptor);
        if (multiView) {
            pass.SetViewport(float(view * viewWidth), 0.0f, float(viewWidth),
                             float(mTarget.height()), 0.0f, 1.0f);
        }
        if (mStrategy) {
            RenderEncoder encoder(pass, result.counters);
            encoder.setTrace(trace);
            mStrategy->encode(encoder, FrameState{cameras[view], timeSeconds, mTimer});
        }
        pass.End();
    }
    if (mTimer) {
        mTimer->resolve(commandEncoder);
    }
    wgpu::CommandBuffer commands = commandEncoder.Finish();
    result.encodeMilliseconds = millisecondsSince(encodeStart);

    const auto submitStart = std::chrono::steady_clock::now();
    mContext->queue().Submit(1, &commands);
    result.submitMilliseconds = millisecondsSince(submitStart);
    if (mStrategy) {
        result.bundleContents = mStrategy->bundleContents();
    }
    if (mTimer) {
        result.gpuMilliseconds = mTimer->read(*mContext);
    }
    return result;
}

Result<void> Renderer::updateInstance(std::size_t instance, const glm::mat4& world) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    return mStrategy->updateInstance(instance, world);
}

Result<void> Renderer::updateMaterial(scene::MaterialId material, const scene::Material& value) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    return mStrategy->updateMaterial(material, value);
}

Result<void> Renderer::replaceBaseColorImage(scene::MaterialId material,
                                             const scene::Image& image) {
    if (!mStrategy) {
        return makeError(ErrorCode::InvalidArgument, "No scene is prepared.");
    }
    ENCORE_TRY(mStrategy->replaceBaseColorImage(material, image));
    return mContext->checkNoErrors("Replacing a base colour image");
}

Result<image::ImageRgba8> Renderer::readImage() {
    auto image = gpu::readTexture(*mContext, mTarget.colorTexture());
    if (!image) {
        return image.error();
    }
    ENCORE_TRY(mContext->checkNoErrors("Rendering"));
    return image;
}

}  // namespace encore::render
