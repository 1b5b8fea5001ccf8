#include "batch/BatchRenderer.h"

#include <algorithm>

#include "encore/image/HdrImage.h"
#include "gpu/ResourcePool.h"
#include "gpu/StagingBuffers.h"
#include "render/renderer/RendererCore.h"

namespace encore::batch {

BatchRenderer::BatchRenderer(gpu::Context& context) : mContext(context) {}

BatchRenderer::~BatchRenderer() {
    discard();
}

void BatchRenderer::discard() {
    // The ring first: it waits for reads of the renderer's target still in flight.
    mRing.reset();
    mStaging.reset();  // Waits for its pending mappings.
    mPngRows.reset();
    mRenderers.clear();
    mResources.reset();  // After the renderers, whose scenes give their resources back to it.
    mRendererOptions.reset();
    mEnvironment.reset();
    mRenderersEnvironment.reset();
    mFileEnvironments.clear();
    mEnvironmentImage.reset();
    mEnvironmentShaders.reset();
    mDevice = nullptr;
}

Result<std::shared_ptr<render::Environment>> BatchRenderer::environmentFor(
    const render::RendererOptions& options) {
    if (options.environment) {
        return options.environment;  // The caller's own: nothing to build.
    }
    if (mEnvironment && mEnvironmentImage == options.environmentImage &&
        mEnvironmentOptions == options.environmentOptions) {
        return mEnvironment;
    }
    // What Renderer::create would build from these options, built here so it outlives the
    // renderer.
    mEnvironment.reset();
    if (!mEnvironmentShaders) {
        mEnvironmentShaders = std::make_unique<shaders::ShaderLibrary>(mContext.device());
    }
    const image::HdrImage panorama =
        options.environmentImage ? *options.environmentImage : image::makeStudioEnvironment();
    auto created =
        render::Environment::create(mContext.device(), mContext.queue(), *mEnvironmentShaders,
                                    panorama, options.environmentOptions);
    if (!created) {
        return created.error().withContext("Creating the environment");
    }
    mEnvironment = std::make_shared<render::Environment>(std::move(*created));
    mEnvironmentImage = options.environmentImage;
    mEnvironmentOptions = options.environmentOptions;
    ++mCounts.environments;
    return mEnvironment;
}

Result<std::shared_ptr<render::Environment>> BatchRenderer::environmentFromFile(
    const std::filesystem::path& file,
    const render::EnvironmentOptions& options) {
    if (mDevice.Get() != mContext.device().Get()) {
        discard();  // A new device (after a loss).
        mDevice = mContext.device();
    }
    ++mEnvironmentUses;
    for (FileEnvironment& kept : mFileEnvironments) {
        if (kept.file == file && kept.options == options) {
            kept.lastUse = mEnvironmentUses;
            return kept.environment;
        }
    }
    auto panorama = image::readHdr(file);
    if (!panorama) {
        return panorama.error().withContext("Reading the environment '" + file.string() + "'");
    }
    if (!mEnvironmentShaders) {
        mEnvironmentShaders = std::make_unique<shaders::ShaderLibrary>(mContext.device());
    }
    auto created = render::Environment::create(mContext.device(), mContext.queue(),
                                               *mEnvironmentShaders, *panorama, options);
    if (!created) {
        return created.error().withContext("Creating the environment of '" + file.string() + "'");
    }
    ++mCounts.environments;
    auto environment = std::make_shared<render::Environment>(std::move(*created));
    if (mFileEnvironments.size() >= kEnvironmentCacheSize) {
        // The one used longest ago goes; renderers still lighting with it keep it alive.
        const auto oldest =
            std::min_element(mFileEnvironments.begin(), mFileEnvironments.end(),
                             [](const FileEnvironment& a, const FileEnvironment& b) {
                                 return a.lastUse < b.lastUse;
                             });
        mFileEnvironments.erase(oldest);
    }
    mFileEnvironments.push_back({file, options, environment, mEnvironmentUses});
    return environment;
}

Result<void> BatchRenderer::light(render::Renderer& renderer, const ModelLighting& lighting) {
    std::shared_ptr<render::Environment> environment = mRenderersEnvironment;
    if (!lighting.environmentFile.empty()) {
        ENCORE_TRY_ASSIGN(
            environment, environmentFromFile(lighting.environmentFile,
                                             mRendererOptions ? mRendererOptions->environmentOptions
                                                              : render::EnvironmentOptions{}));
    }
    renderer.setEnvironment(std::move(environment));
    render::LightingParameters parameters = renderer.lighting();
    parameters.environmentRotationRadians = lighting.rotationRadians;
    parameters.environmentIntensity = lighting.intensity;
    renderer.setLighting(parameters);
    return {};
}

const std::shared_ptr<gpu::StagingBuffers>& BatchRenderer::staging() {
    if (!mStaging) {
        mStaging = std::make_shared<gpu::StagingBuffers>(mContext);
    }
    return mStaging;
}

Result<PngRowsPass*> BatchRenderer::pngRowsPass() {
    if (!mPngRows) {
        ENCORE_TRY_ASSIGN(auto pass, PngRowsPass::create(mContext.device()));
        mPngRows.emplace(std::move(pass));
    }
    return &*mPngRows;
}

Result<void> BatchRenderer::acquire(const render::RendererOptions& options,
                                    std::size_t readbackSlots,
                                    std::size_t rendererCount) {
    if (mDevice.Get() != mContext.device().Get()) {
        discard();  // A new device (after a loss): nothing built on the old one is of use.
        mDevice = mContext.device();
    }
    if (!mRenderers.empty() && mRendererOptions == options && mReadbackSlots == readbackSlots &&
        mRenderers.size() == rendererCount) {
        // The previous batch left the scene it prepared last released (runBatch's end).
        return {};
    }
    mRing.reset();
    mRenderers.clear();
    mRendererOptions.reset();
    mResources = std::make_unique<gpu::ResourcePool>(mContext.device());
    ENCORE_TRY_ASSIGN(auto environment, environmentFor(options));
    render::RendererOptions built = options;
    built.environment = environment;
    for (std::size_t i = 0; i < std::max<std::size_t>(rendererCount, 1); ++i) {
        auto renderer = render::Renderer::create(mContext, built);
        if (!renderer) {
            mRenderers.clear();
            return renderer.error();
        }
        mRenderers.push_back(std::move(*renderer));
        internals(mRenderers.back()).setResourcePool(mResources.get());
    }
    mRenderersEnvironment = environment;
    mRendererOptions = options;
    mReadbackSlots = readbackSlots;
    mRing = std::make_unique<gpu::TextureReadbackRing>(mContext, readbackSlots);
    ++mCounts.renderers;
    return {};
}

}  // namespace encore::batch
