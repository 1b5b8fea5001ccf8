#pragma once

// The samples a batch makes of one model: the model with its default materials, in one
// KHR_materials_variants variant (BatchOptions::variant), or with its default materials and in
// every variant (BatchOptions::allVariants), each sample into a folder of its own
// (variantSampleNames) and finished on its own.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "encore/batch/Batch.h"
#include "encore/batch/BatchInputs.h"
#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::batch {

struct ModelSample {
    std::optional<scene::VariantId> variant;  // nullopt: the default materials.
    std::string variantName;                  // Empty for the default materials.
    std::string name;                         // The output name.
};

// The samples of `input`, whose variants are `variants` (SceneData::variants). Fails with
// InvalidArgument, naming the file and its variants, when BatchOptions::variant names none.
Result<std::vector<ModelSample>> modelSamples(const BatchOptions& options,
                                              const BatchInput& input,
                                              std::span<const std::string> variants);

// Whether every sample of `input` is finished, decided before loading it: the variant names are
// read from the file's JSON (scene::readVariantNames) only when the samples depend on them, and
// with allVariants only once the default sample is finished. A file whose names cannot be read
// is not finished (its load says why).
bool samplesFinished(const BatchOptions& options, const BatchInput& input);

}  // namespace encore::batch
