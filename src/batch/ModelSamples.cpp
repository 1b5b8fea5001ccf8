#include "batch/ModelSamples.h"

#include "batch/ModelOutput.h"
#include "encore/scene/SceneData.h"

namespace encore::batch {

Result<std::vector<ModelSample>> modelSamples(const BatchOptions& options,
                                              const BatchInput& input,
                                              std::span<const std::string> variants) {
    const std::vector<std::string> names = variantSampleNames(input.name, variants);
    std::vector<ModelSample> samples;
    if (!options.variant.empty()) {
        ENCORE_TRY_ASSIGN(const scene::VariantId variant,
                          scene::resolveVariant(variants, options.variant, input.path.string()));
        samples.push_back({variant, variants[variant.index()], names[variant.index()]});
        return samples;
    }
    samples.push_back({std::nullopt, {}, input.name});
    if (options.allVariants) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
            samples.push_back({scene::VariantId(v), variants[v], names[v]});
        }
    }
    return samples;
}

bool samplesFinished(const BatchOptions& options, const BatchInput& input) {
    const auto finished = [&](const std::string& name) {
        return modelFinished(modelFolder(options.output, name), modelFileSet(options));
    };
    if (options.variant.empty()) {
        // The default sample decides alone, or first (no file is read for an unfinished one).
        if (!finished(input.name)) {
            return false;
        }
        if (!options.allVariants) {
            return true;
        }
    }
    const auto variants = scene::readVariantNames(input.path);
    if (!variants) {
        return false;
    }
    const auto samples = modelSamples(options, input, *variants);
    if (!samples) {
        return false;
    }
    for (const ModelSample& sample : *samples) {
        if (!finished(sample.name)) {
            return false;
        }
    }
    return true;
}

}  // namespace encore::batch
