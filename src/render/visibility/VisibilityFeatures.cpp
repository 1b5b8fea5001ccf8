#include "render/visibility/VisibilityFeatures.h"

#include <algorithm>

namespace encore::render {

void requestVisibilityFeatures(gpu::ContextOptions& options) {
    options.allowUnsafeApis = true;
    auto& features = options.optionalFeatures;
    if (std::find(features.begin(), features.end(), kVisibilityFeature) == features.end()) {
        features.push_back(kVisibilityFeature);
    }
}

}  // namespace encore::render
