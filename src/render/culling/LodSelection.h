#pragma once

// How a frame chooses levels of detail, shared by GPU culling (culling.wgsl) and the visibility
// strategy (visibility_cull.wgsl) so that both pick the same level for the same instance: the
// coarsest level whose object-space error, times the pixels one unit covers at the instance's
// nearest point (its bounding sphere's box, seen from the nearest of `views`), stays under
// `thresholdPixels`.

#include <array>
#include <cstdint>
#include <span>

#include <glm/vec4.hpp>

#include "encore/render/Camera.h"
#include "encore/render/RendererOptions.h"

namespace encore::render {

struct LodSelection {
    // Views whose positions levels of detail are chosen from; a frame of more uses a bound
    // around them (the shaders' lodViews arrays).
    static constexpr std::size_t kMaxViews = 16;

    std::array<glm::vec4, kMaxViews> views{};  // xyz: a view's position.
    std::uint32_t viewCount = 0;
    // Pixels that one unit at distance one covers (orthographic: at any distance); 0: levels of
    // detail off.
    float pixelsPerUnit = 0.0f;
    float thresholdPixels = 0.0f;
    std::uint32_t orthographic = 0;
    // Subtracted from the distance to the nearest view (a frame of more than kMaxViews views).
    float distanceSlack = 0.0f;
};

// `camera` culls; `views` are all views of a multi-view frame that one cull serves (empty or one
// for a frame of one view).
LodSelection lodSelection(const Camera& camera,
                          std::span<const Camera> views,
                          std::uint32_t targetHeight,
                          const CullingOptions& options);

}  // namespace encore::render
