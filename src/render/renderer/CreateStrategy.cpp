#include "render/renderer/CreateStrategy.h"

#include "render/strategies/BundledStrategy.h"
#include "render/strategies/BundlesStrategy.h"
#include "render/strategies/GpuCullingStrategy.h"
#include "render/strategies/InstancingStrategy.h"
#include "render/strategies/LayoutsStrategy.h"
#include "render/strategies/MaterialsStrategy.h"
#include "render/strategies/NaiveStrategy.h"
#include "render/strategies/PipelineCacheStrategy.h"
#include "render/visibility/VisibilityStrategy.h"

namespace encore::render {

std::unique_ptr<Strategy> createStrategy(StrategyKind kind, bool bundle) {
    if (bundle) {
        if (auto bundled = bundledKind(kind)) {
            return createStrategy(*bundled);
        }
        return std::make_unique<BundledStrategy>(createStrategy(kind));
    }
    switch (kind) {
        case StrategyKind::Naive:
            return std::make_unique<NaiveStrategy>();
        case StrategyKind::Layouts:
            return std::make_unique<LayoutsStrategy>();
        case StrategyKind::PipelineCache:
            return std::make_unique<PipelineCacheStrategy>();
        case StrategyKind::Instancing:
            return std::make_unique<InstancingStrategy>();
        case StrategyKind::Materials:
            return std::make_unique<MaterialsStrategy>();
        case StrategyKind::Bundles:
            return std::make_unique<BundlesStrategy>();
        case StrategyKind::GpuCulling:
            return std::make_unique<GpuCullingStrategy>(false);
        case StrategyKind::GpuCullingBundles:
            return std::make_unique<GpuCullingStrategy>(true);
        case StrategyKind::Visibility:
            return std::make_unique<VisibilityStrategy>();
    }
    return nullptr;
}

}  // namespace encore::render
