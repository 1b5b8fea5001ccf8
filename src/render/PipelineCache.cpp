#include "render/PipelineCache.h"

#include <string>

#include "render/RenderSetup.h"

namespace encore::render {

Result<wgpu::RenderPipeline> PipelineCache::get(const PipelineKey& key) {
    if (auto found = mPipelines.find(key); found != mPipelines.end()) {
        ++mHits;
        return found->second;
    }
    ENCORE_TRY_ASSIGN(auto pipeline,
                      createMeshPipeline(*mSetup, key,
                                         "cached pipeline " + std::to_string(mPipelines.size()) +
                                             " (" + key.shader.describe() + ")"));
    mPipelines.emplace(key, pipeline);
    return pipeline;
}

PipelineCache* strategyPipelineCache(const RenderSetup& setup,
                                     std::unique_ptr<PipelineCache>& own) {
    if (setup.keptPipelines) {
        own.reset();
        return setup.keptPipelines;
    }
    own = std::make_unique<PipelineCache>(setup);
    return own.get();
}

}  // namespace encore::render
