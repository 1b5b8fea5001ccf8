#include "batch/ModelPlan.h"

#include <algorithm>

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
    job.views = viewCameras(options.views, job.model->input->name);
    job.lighting = modelLighting(options.lighting, mEnvironments, options.renderer.lighting,
                                 options.views.seed, job.model->input->name);
    // Only a transparent background leaves alpha to count coverage by.
    if (options.renderer.toneMapping.background == render::BackgroundKind::Transparent) {
        job.coveredPixels.assign(job.views.size(), 0);
    }
}

void ModelPlanner::groupByEnvironment(std::vector<BatchInput>& inputs) const {
    if (mEnvironments.size() < 2) {
        return;
    }
    std::vector<std::pair<std::size_t, BatchInput>> keyed;
    for (BatchInput& input : inputs) {
        keyed.emplace_back(environmentIndex(mEnvironments.size(), mOptions->views.seed, input.name),
                           std::move(input));
    }
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        inputs[i] = std::move(keyed[i].second);
    }
}

}  // namespace encore::batch
