#include "batch/BatchOptionsValidation.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace encore::batch {
namespace {

// "1.5", or "1.5 to 2.2" for a range.
std::string rangeText(const ValueRange& range) {
    std::ostringstream text;
    text << range.min;
    if (!range.fixed()) {
        text << " to " << range.max;
    }
    return text.str();
}

// Written as negations of what is valid so that NaN fails them too.
bool ordered(const ValueRange& range) {
    return range.min <= range.max && std::isfinite(range.min) && std::isfinite(range.max);
}

// The lists of --azimuths, --elevations and --distances: values in range (distances positive),
// and the lists of several values of one length.
Result<void> checkLists(const ViewRigOptions& rig) {
    const struct {
        const char* name;
        const std::vector<float>& values;
        float limit;  // |value| <= limit; 0: positive.
    } lists[] = {{"azimuths", rig.azimuthsDegrees, 360.0f},
                 {"elevations", rig.elevationsDegrees, 90.0f},
                 {"distances", rig.distances, 0.0f}};
    std::size_t length = 1;
    const char* lengthFrom = nullptr;
    for (const auto& list : lists) {
        for (const float value : list.values) {
            const bool valid = list.limit > 0.0f ? std::abs(value) <= list.limit
                                                 : value > 0.0f && std::isfinite(value);
            if (!valid) {
                std::ostringstream text;
                text << "The camera " << list.name << " must ";
                if (list.limit > 0.0f) {
                    text << "lie in [" << -list.limit << ", " << list.limit << "]";
                } else {
                    text << "be positive";
                }
                text << " (not " << value << ").";
                return makeError(ErrorCode::InvalidArgument, text.str());
            }
        }
        if (list.values.size() > 1) {
            if (lengthFrom && list.values.size() != length) {
                return makeError(ErrorCode::InvalidArgument,
                                 std::string("The camera ") + lengthFrom + " and " + list.name +
                                     " lists differ in length (" + std::to_string(length) +
                                     " and " + std::to_string(list.values.size()) +
                                     "): each holds one value per view, or one for all.");
            }
            length = list.values.size();
            lengthFrom = list.name;
        }
    }
    return {};
}

Result<void> checkCameras(const ViewRigOptions& rig) {
    const ValueRange& fov = rig.horizontalFovDegrees;
    if (!(ordered(fov) && fov.min > 0.0f && fov.max < 180.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The field of view (" + rangeText(fov) +
                             " degrees) must lie in (0, 180), a range with its minimum first.");
    }
    if (!(ordered(rig.distance) && rig.distance.min > 0.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The camera distance (" + rangeText(rig.distance) +
                             ") must be positive, a range with its minimum first.");
    }
    if (!(ordered(rig.elevationDegrees) && rig.elevationDegrees.min >= -90.0f &&
          rig.elevationDegrees.max <= 90.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The elevation (" + rangeText(rig.elevationDegrees) +
                             " degrees) must lie in [-90, 90], a range with its minimum first.");
    }
    ENCORE_TRY(checkLists(rig));
    if (rig.projection == Projection::Orthographic && !(rig.orthoScale > 0.0f)) {
        return makeError(
            ErrorCode::InvalidArgument,
            "The orthographic scale (" + rangeText(rig.orthoScale) + ") must be positive.");
    }
    if (!(rig.jitterDegrees >= 0.0f && rig.jitterDegrees <= 180.0f)) {
        return makeError(ErrorCode::InvalidArgument, "The camera jitter (" +
                                                         rangeText(rig.jitterDegrees) +
                                                         " degrees) must lie in [0, 180].");
    }
    return {};
}

Result<void> checkLighting(const BatchOptions& options) {
    const LightingVariation& lighting = options.lighting;
    if (lighting.intensity && !(ordered(*lighting.intensity) && lighting.intensity->min >= 0.0f)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The environment intensity (" + rangeText(*lighting.intensity) +
                             ") must be 0 or more, a range with its minimum first.");
    }
    if (lighting.rotationDegrees && !ordered(*lighting.rotationDegrees)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The environment rotation (" + rangeText(*lighting.rotationDegrees) +
                             " degrees) must be finite, a range with its minimum first.");
    }
    if (!lighting.environmentDirectory.empty() &&
        (options.renderer.environment || options.renderer.environmentImage)) {
        return makeError(ErrorCode::InvalidArgument,
                         "An environment folder ('" + lighting.environmentDirectory.string() +
                             "') and an environment of the renderer options exclude each other.");
    }
    return {};
}

}  // namespace

render::StrategyChoice batchStrategy(const BatchOptions& options) {
    return options.strategy.value_or(render::StrategyChoice::of(
        options.lodErrorPixels > 0.0f ? render::StrategyKind::GpuCullingBundles
                                      : render::StrategyKind::Bundles,
        false));
}

Result<void> validateBatchOptions(const BatchOptions& options) {
    const ViewRigOptions& rig = options.views;
    if (options.width == 0 || options.height == 0 || viewCount(rig) == 0) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch needs at least one view of at least one pixel.");
    }
    ENCORE_TRY(checkCameras(rig));
    ENCORE_TRY(checkLighting(options));
    const render::StrategyChoice strategy = batchStrategy(options);
    // GPU culling and the visibility strategy's cull choose levels; the others draw level 0.
    const bool choosesLevels =
        render::cullsOnTheGpu(strategy.kind) || strategy.kind == render::StrategyKind::Visibility;
    if (!(options.lodErrorPixels >= 0.0f) || (options.lodErrorPixels > 0.0f && !choosesLevels)) {
        return makeError(ErrorCode::InvalidArgument,
                         "Levels of detail (an error of " + std::to_string(options.lodErrorPixels) +
                             " pixels) need a non-negative error and a gpu-culling or the "
                             "visibility strategy, which chooses the levels (not " +
                             render::strategyChoiceName(strategy) + ").");
    }
    if ((options.strategy || !options.chooseStrategyPerModel) && options.visibilityFromTriangles) {
        return makeError(ErrorCode::InvalidArgument,
                         "A triangle count from which models are drawn with visibility (" +
                             std::to_string(*options.visibilityFromTriangles) +
                             ") applies to the automatic choice only (--strategy auto), not to " +
                             render::strategyChoiceName(batchStrategy(options)) + ".");
    }
    if (options.allVariants && !options.variant.empty()) {
        return makeError(ErrorCode::InvalidArgument, "A batch renders one material variant ('" +
                                                         options.variant +
                                                         "') or all of them, not both.");
    }
    if (options.images.depthFormat == DepthFormat::Exr && !options.images.depth) {
        return makeError(ErrorCode::InvalidArgument,
                         "An EXR depth format asks for depth images: add --depth (depth=True).");
    }
    const bool meshMaterials = strategy.kind == render::StrategyKind::Materials ||
                               strategy.kind == render::StrategyKind::Bundles ||
                               strategy.kind == render::StrategyKind::GpuCulling ||
                               strategy.kind == render::StrategyKind::GpuCullingBundles;
    // Geometric normals and positions are debug channels of the glTF materials' shading too.
    if ((options.images.albedo || options.images.material || options.images.segmentation ||
         options.images.coordinates ||
         (options.images.normals && options.images.normalKind == NormalKind::Geometric)) &&
        !meshMaterials) {
        return makeError(ErrorCode::InvalidArgument,
                         "The albedo, material, segmentation and coordinates passes and geometric "
                         "normals need a strategy that "
                         "draws glTF materials in its mesh shader (materials, bundles, "
                         "gpu-culling, gpu-culling-bundles), not " +
                             render::strategyChoiceName(strategy) + ".");
    }
    if (!(options.modelTimeoutSeconds >= 0.0) || !std::isfinite(options.modelTimeoutSeconds)) {
        return makeError(ErrorCode::InvalidArgument,
                         "The model time limit must be a number of seconds, 0 for none (not " +
                             std::to_string(options.modelTimeoutSeconds) + ").");
    }
    if (options.renderers < 1 || options.renderers > kMaxRenderers) {
        return makeError(ErrorCode::InvalidArgument,
                         "A batch takes 1 to " + std::to_string(kMaxRenderers) +
                             " renderers (asked for " + std::to_string(options.renderers) + ").");
    }
    return {};
}

}  // namespace encore::batch
