#include "batch/ModelPlan.h"

namespace encore::batch {

Result<ModelPlanner> ModelPlanner::create(const BatchOptions& options) {
    ModelPlanner planner(options);
    if (!options.lighting.environmentDirectory.empty()) {
        ENCORE_TRY_ASSIGN(planner.mEnvironments,
                          environmentFiles(options.lighting.environmentDirectory));
    }
    return planner;
}

void ModelPlanner::plan(ModelJob& job) const {
    const BatchOptions& options = *mOptions;
    job.views = viewCameras(options.views, job.input->name);
    job.lighting = modelLighting(options.lighting, mEnvironments, options.renderer.lighting,
                                 options.views.seed, job.input->name);
    // Only a transparent background leaves alpha to count coverage by.
    if (options.renderer.toneMapping.background == render::BackgroundKind::Transparent) {
        job.coveredPixels.assign(job.views.size(), 0);
    }
}

}  // namespace encore::batch
