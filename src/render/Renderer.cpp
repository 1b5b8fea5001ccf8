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
    ENCORE_TRY(context.checkNoErrors("Creating the renderer"));
    return renderer;
}

Result<void> Renderer::prepare(const scene::SceneData& scene, StrategyKind kind) {
    mStrategy.reset();  // Release the previous strategy's resources first.
    mSetup->pipelinesCreated = 0;
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
    FrameResult result;
    mFrame->update(mContext->queue(), camera, timeSeconds);

    const auto encodeStart = std::chrono::steady_clock::now();
    wgpu::CommandEncoder commandEncoder = mContext->device().CreateCommandEncoder();
    wgpu::RenderPassColorAttachment color = mTarget.colorAttachment(mOptions.clearColor);
    wgpu::RenderPassDepthStencilAttachment depth = mTarget.depthAttachment();
    wgpu::RenderPassDescriptor passDescriptor{};
    passDescriptor.colorAttachmentCount = 1;
    passDescriptor.colorAttachments = &color;
    passDescriptor.depthStencilAttachment = &depth;
    wgpu::RenderPassEncoder pass = commandEncoder.BeginRenderPass(&passDescriptor);
    if (mStrategy) {
        RenderEncoder encoder(pass, result.counters);
        encoder.setTrace(trace);
        mStrategy->encode(encoder, FrameState{camera, timeSeconds});
    }
    pass.End();
    wgpu::CommandBuffer commands = commandEncoder.Finish();
    result.encodeMilliseconds = millisecondsSince(encodeStart);

    const auto submitStart = std::chrono::steady_clock::now();
    mContext->queue().Submit(1, &commands);
    result.submitMilliseconds = millisecondsSince(submitStart);
    return result;
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
