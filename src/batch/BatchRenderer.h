#pragma once

// What a batch builds on its device before it renders a model, kept for the batches after it:
// the renderer (render target, image-based light, the pipelines it keeps from one model to the
// next), the ring of read-back buffers, the pool of buffers and textures the models' scenes
// reuse, the staging buffers uploads go through and the PNG rows' compute pass.
//
// runBatch builds these once per call. A caller that runs many batches on one device in turn
// (encore.Renderer.batch, called once per Dask task on a worker) keeps one BatchRenderer and
// hands it to every runBatch: only the first builds, and the batches after it start at once with
// the pipelines already created, as the models of one long batch do. What is kept is rebuilt only
// when a batch asks for different options: a new size or sample count makes a new renderer (and
// ring) but keeps the environment maps; a new environment image or environment options rebuild
// those too. The images are those of a fresh build, byte for byte.
//
// A batch that lights each model with one of a folder's panoramas (BatchLighting.h) gets their
// environment maps from here too: computed once per file and kept, the kEnvironmentCacheSize
// used last, so models lit by the same file share them and a renderer switches between them for
// the price of one bind group.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "batch/PngRowsPass.h"
#include "encore/batch/BatchLighting.h"
#include "encore/core/Result.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "gpu/TextureReadbackRing.h"
#include "render/Environment.h"
#include "shaders/ShaderLibrary.h"

namespace encore::gpu {
class ResourcePool;
class StagingBuffers;
}  // namespace encore::gpu

namespace encore::batch {

// How often a BatchRenderer built what it keeps: what tells reuse from rebuilding.
struct BatchRendererCounts {
    std::size_t renderers = 0;     // Times the renderers (and the ring) were built.
    std::size_t environments = 0;  // Environment maps computed (the options' and files').
};

// Environment maps of files kept at most: each holds about 13 MiB of textures at the default
// EnvironmentOptions (its cube maps and atlas) and its panorama on the CPU; computing one costs
// reading the file and about a second of GPU work on lavapipe.
inline constexpr std::size_t kEnvironmentCacheSize = 8;

class BatchRenderer {
  public:
    // The context must outlive this object.
    explicit BatchRenderer(gpu::Context& context);
    ~BatchRenderer();
    BatchRenderer(const BatchRenderer&) = delete;
    BatchRenderer& operator=(const BatchRenderer&) = delete;

    // Makes renderer(0) .. renderer(rendererCount - 1) ones built from `options`, lighting with
    // one environment, with a ring of `readbackSlots` read-back buffers: those already kept when
    // they were built from equal options and count, otherwise new ones. The environment
    // maps are kept when `options` names the same environment source (no `environment` of its
    // own, the same `environmentImage` object, equal `environmentOptions`). No scene is prepared
    // on return.
    Result<void> acquire(const render::RendererOptions& options,
                         std::size_t readbackSlots,
                         std::size_t rendererCount = 1);

    // Valid after a successful acquire() until the next acquire() or discard().
    render::Renderer& renderer(std::size_t index = 0) { return mRenderers[index]; }
    std::size_t rendererCount() const { return mRenderers.size(); }
    gpu::TextureReadbackRing& ring() { return *mRing; }
    // The staging buffers of the models' uploads, whatever the options, after acquire(). Kept
    // from batch to batch: made anew, their first mappings cost the first models of each batch
    // (and a Dask task's batch is a few models).
    const std::shared_ptr<gpu::StagingBuffers>& staging();
    // The pass that filters PNG rows on the GPU (PngRowsPass.h), after acquire(): compiled by
    // the first batch that asks for it and kept.
    Result<PngRowsPass*> pngRowsPass();
    bool ready() const { return !mRenderers.empty(); }

    // The environment maps of the Radiance .hdr `file` with `options`: computed on the first
    // call, then kept (the kEnvironmentCacheSize used last). Errors name the file.
    Result<std::shared_ptr<render::Environment>> environmentFromFile(
        const std::filesystem::path& file,
        const render::EnvironmentOptions& options);
    // Lights `renderer` (one of this object's, after acquire()) as `lighting` says: its
    // environment (the file's, or the one acquire() built the renderers with) from the
    // renderer's next prepare(), the rotation and intensity at once.
    Result<void> light(render::Renderer& renderer, const ModelLighting& lighting);

    // Forgets everything it built: after a device loss its objects belong to the lost device.
    // (acquire() also rebuilds by itself when the context's device is not the one it built on.)
    void discard();

    gpu::Context& context() { return mContext; }

    const BatchRendererCounts& counts() const { return mCounts; }

  private:
    Result<std::shared_ptr<render::Environment>> environmentFor(
        const render::RendererOptions& options);

    gpu::Context& mContext;
    BatchRendererCounts mCounts;
    // The device everything below was built on; held, so that a new device never compares
    // equal to it.
    wgpu::Device mDevice;
    // Compiles the environment's passes; the environment keeps a pointer to it (Environment::
    // load), so it outlives mEnvironment.
    std::unique_ptr<shaders::ShaderLibrary> mEnvironmentShaders;
    std::shared_ptr<render::Environment> mEnvironment;
    // What the renderers were built with: mEnvironment, or the options' own.
    std::shared_ptr<render::Environment> mRenderersEnvironment;
    struct FileEnvironment {
        std::filesystem::path file;
        render::EnvironmentOptions options;
        std::shared_ptr<render::Environment> environment;
        std::uint64_t lastUse = 0;
    };
    std::vector<FileEnvironment> mFileEnvironments;  // At most kEnvironmentCacheSize.
    std::uint64_t mEnvironmentUses = 0;
    // What mEnvironment was computed from.
    std::shared_ptr<const image::HdrImage> mEnvironmentImage;
    render::EnvironmentOptions mEnvironmentOptions;
    // The buffers and textures the renderers' scenes take and give back, so that a model in
    // steady state creates none (gpu/ResourcePool.h). Before mRenderers: it outlives their scenes.
    std::unique_ptr<gpu::ResourcePool> mResources;
    std::vector<render::Renderer> mRenderers;
    std::optional<render::RendererOptions> mRendererOptions;  // As acquire() was given them.
    std::size_t mReadbackSlots = 0;
    // After mRenderers: destroyed first, it waits for reads of the renderers' targets.
    std::unique_ptr<gpu::TextureReadbackRing> mRing;
    std::shared_ptr<gpu::StagingBuffers> mStaging;
    std::optional<PngRowsPass> mPngRows;
};

}  // namespace encore::batch
