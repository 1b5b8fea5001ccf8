#pragma once

// Render pipelines cached by PipelineKey: one pipeline per distinct combination of every
// pipeline argument, created on first use.

#include <webgpu/webgpu_cpp.h>

#include <memory>
#include <unordered_map>

#include "encore/core/Result.h"
#include "render/PipelineKey.h"

namespace encore::render {

class PipelineCache {
  public:
    // `setup` must outlive the cache.
    explicit PipelineCache(const RenderSetup& setup) : mSetup(&setup) {}

    Result<wgpu::RenderPipeline> get(const PipelineKey& key);

    std::size_t size() const { return mPipelines.size(); }
    std::size_t hits() const { return mHits; }

  private:
    const RenderSetup* mSetup;
    std::unordered_map<PipelineKey, wgpu::RenderPipeline, PipelineKeyHash> mPipelines;
    std::size_t mHits = 0;
};

// The cache a strategy prepared with `setup` draws with: the renderer's kept cache
// (RenderSetup::keptPipelines, RendererOptions::keepPipelines), or otherwise a new one of the
// strategy's own, created in `own`.
PipelineCache* strategyPipelineCache(const RenderSetup& setup, std::unique_ptr<PipelineCache>& own);

}  // namespace encore::render
