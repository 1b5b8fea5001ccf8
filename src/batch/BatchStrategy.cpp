#include "batch/BatchStrategy.h"

#include "batch/BatchOptionsValidation.h"
#include "encore/gpu/Context.h"
#include "render/visibility/VisibilityFeatures.h"

namespace encore::batch {

render::StrategyChoice BatchStrategy::forModel(std::uint64_t drawnTriangles,
                                               bool opaqueStatic) const {
    return drawnTriangles >= visibilityFromTriangles || (visibilityForOpaqueStatic && opaqueStatic)
               ? render::StrategyChoice::of(render::StrategyKind::Visibility, false)
               : base;
}

bool BatchStrategy::buildsClusters() const {
    return base.kind == render::StrategyKind::Visibility || mayChooseVisibility();
}

std::uint64_t BatchStrategy::clustersFromTriangles() const {
    return base.kind == render::StrategyKind::Visibility ? 0 : visibilityFromTriangles;
}

BatchStrategy batchStrategyFor(const BatchOptions& options,
                               std::span<gpu::Context* const> devices) {
    BatchStrategy strategy{batchStrategy(options)};
    if (options.strategy || !options.chooseStrategyPerModel) {
        return strategy;
    }
    // Normals, depth and the other passes are drawn by the mesh strategies' pass targets.
    if (options.images.perView() > 1) {
        return strategy;
    }
    for (const gpu::Context* device : devices) {
        if (!device->device().HasFeature(render::kVisibilityFeature)) {
            return strategy;
        }
        // An explicit threshold holds on a CPU too (the tests choose it on lavapipe).
        if (device->adapterDescription().adapterType == wgpu::AdapterType::CPU &&
            !options.visibilityFromTriangles) {
            return strategy;
        }
    }
    strategy.visibilityFromTriangles =
        options.visibilityFromTriangles.value_or(autoVisibilityTriangles(options.samples));
    strategy.visibilityForOpaqueStatic =
        !options.visibilityFromTriangles && options.samples > 1 && kAutoVisibilityOpaqueStatic;
    return strategy;
}

}  // namespace encore::batch
