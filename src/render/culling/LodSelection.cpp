#include "render/culling/LodSelection.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace encore::render {

LodSelection lodSelection(const Camera& camera,
                          std::span<const Camera> views,
                          std::uint32_t targetHeight,
                          const CullingOptions& options) {
    LodSelection lod;
    // The projection's y scale maps a unit at distance one (orthographic: anywhere) to that many
    // half-heights of the viewport.
    float projectionScale = camera.projection[1][1];
    if (views.size() > 1) {
        // Levels of detail are chosen for the nearest view. Past kMaxViews views, distances are
        // measured from their centroid less the farthest view's distance from it: never more
        // than the distance to any view.
        for (const Camera& each : views) {
            projectionScale = std::max(projectionScale, each.projection[1][1]);
        }
        if (views.size() <= LodSelection::kMaxViews) {
            for (const Camera& each : views) {
                lod.views[lod.viewCount++] = glm::vec4(each.position, 1.0f);
            }
        } else {
            glm::vec3 centroid(0.0f);
            for (const Camera& each : views) {
                centroid += each.position / float(views.size());
            }
            for (const Camera& each : views) {
                lod.distanceSlack =
                    std::max(lod.distanceSlack, glm::distance(each.position, centroid));
            }
            lod.views[0] = glm::vec4(centroid, 1.0f);
            lod.viewCount = 1;
        }
    } else {
        lod.views[0] = glm::vec4(camera.position, 1.0f);
        lod.viewCount = 1;
    }
    if (options.levelsOfDetail) {
        lod.pixelsPerUnit = projectionScale * float(targetHeight) * 0.5f;
    }
    lod.thresholdPixels = options.lodErrorPixels;
    lod.orthographic = camera.projection[2][3] == 0.0f ? 1u : 0u;
    return lod;
}

}  // namespace encore::render
