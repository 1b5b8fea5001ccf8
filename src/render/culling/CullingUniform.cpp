#include "render/culling/CullingUniform.h"

#include <algorithm>

#include "render/culling/Frustum.h"

namespace encore::render {

void fillCullingView(CullingUniform& uniform,
                     const glm::mat4& viewProjection,
                     bool testFrustum,
                     const LodSelection& lod) {
    uniform.viewProjection = viewProjection;
    if (testFrustum) {
        const Frustum frustum = Frustum::fromViewProjection(viewProjection);
        std::copy(frustum.planes.begin(), frustum.planes.end(), uniform.planes.begin());
    } else {
        uniform.planes.fill(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    }
    uniform.frustumTest = testFrustum ? 1 : 0;
    uniform.lodViews = lod.views;
    uniform.lodViewCount = lod.viewCount;
    uniform.lodPixelsPerUnit = lod.pixelsPerUnit;
    uniform.lodThresholdPixels = lod.thresholdPixels;
    uniform.orthographic = lod.orthographic;
    uniform.lodDistanceSlack = lod.distanceSlack;
}

}  // namespace encore::render
