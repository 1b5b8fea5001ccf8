#pragma once

// Render pipelines cached by PipelineKey: one pipeline per distinct combination of every
// pipeline argument, created on first use.

#include <webgpu/webgpu_cpp.h>

#include <unordered_map>

#include "encore/core/Result.h"
#include "encore/render/PipelineKey.h"

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

}  // namespace encore::render
