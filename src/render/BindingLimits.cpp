#include "render/BindingLimits.h"

#include <string>

namespace encore::render {

Result<void> checkBindingLimits(const gpu::DeviceLimits& limits, std::string_view adapter) {
    if (limits.maxSampledTexturesPerShaderStage >= kStageSampledTextures) {
        return {};
    }
    return makeError(
        ErrorCode::LimitExceeded,
        "The adapter '" + std::string(adapter) + "' offers " +
            std::to_string(limits.maxSampledTexturesPerShaderStage) +
            " sampled textures per shader stage (maxSampledTexturesPerShaderStage), fewer than "
            "the " +
            std::to_string(kStageSampledTextures) + " Encore's materials bind (" +
            std::to_string(kMaterialTextureSlotCount) + " texture slots and " +
            std::to_string(kFrameSampledTextures) +
            " for the environment and the transmission background).");
}

}  // namespace encore::render
