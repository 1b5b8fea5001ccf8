#pragma once

// What a batch decides for each model before drawing it: its views (ViewRig.h) and its lighting
// (BatchLighting.h), both drawn from the batch's seed and the model's name, and whether its
// views' coverage is counted (blank views).

#include <filesystem>
#include <vector>

#include "batch/ModelWriter.h"
#include "encore/batch/Batch.h"
#include "encore/core/Result.h"

namespace encore::batch {

class ModelPlanner {
  public:
    // Lists the environment folder of `options` (which must outlive the planner) if it names
    // one: InvalidArgument when it is not a folder or holds no .hdr file.
    static Result<ModelPlanner> create(const BatchOptions& options);

    // Sets the views, the lighting and the coverage counters of `job`, whose input is set.
    void plan(ModelJob& job) const;

    // Puts the models lit by the same environment file next to each other (in file order, each
    // group in its given order), so that each file's maps are computed once per run however few
    // BatchRenderer keeps: nothing drawn depends on the order. Without a folder, or with one
    // file, the order stays.
    void groupByEnvironment(std::vector<BatchInput>& inputs) const;

  private:
    explicit ModelPlanner(const BatchOptions& options) : mOptions(&options) {}

    const BatchOptions* mOptions;
    std::vector<std::filesystem::path> mEnvironments;
};

}  // namespace encore::batch
