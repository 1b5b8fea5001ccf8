#include "batch/BatchOptionsValidation.h"

#include <string>

namespace encore::batch {

render::StrategyChoice batchStrategy(const BatchOptions& options) {
    return options.strategy.value_or(render::StrategyChoice::of(
        options.lodErrorPixels > 0.0f ? render::StrategyKind::GpuCullingBundles
                                      : render::StrategyKind::Bundles,
        false));
}

Result<void> validateBatchOptions(const BatchOptions& options) {
    const ViewRigOptions& rig = options.views;
    if (options.width == 0 || options.height == 0 || rig.views == 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch needs at least one view of at least one pixel.");
    }
    // Written as negations so that NaN fails them too.
    if (!(rig.horizontalFovDegrees > 0.0f && rig.horizontalFovDegrees < 180.0f) ||
        !(rig.distance > 0.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The field of view (" + std::to_string(rig.horizontalFovDegrees) +
                             " degrees) must lie in (0, 180) and the distance (" +
                             std::to_string(rig.distance) + ") must be positive.");
    }
    const render::StrategyChoice strategy = batchStrategy(options);
    if (!(options.lodErrorPixels >= 0.0f) ||
        (options.lodErrorPixels > 0.0f && !render::cullsOnTheGpu(strategy.kind))) {
        return makeError(ErrorCode::InvalidArgument,
                         "Levels of detail (an error of " + std::to_string(options.lodErrorPixels) +
                             " pixels) need a non-negative error and a gpu-culling strategy, "
                             "which chooses the levels (not " +
                             render::strategyChoiceName(strategy) + ").");
    }
    if (options.allVariants && !options.variant.empty()) {
        return makeError(ErrorCode::InvalidArgument, "A batch renders one material variant ('" +
                                                         options.variant +
                                                         "') or all of them, not both.");
    }
    if (options.renderers < 1 || options.renderers > kMaxRenderers) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch takes 1 to " + std::to_string(kMaxRenderers) +
                             " renderers (asked for " + std::to_string(options.renderers) + ").");
    }
    return {};
}

}  // namespace encore::batch
