#pragma once

// The frame's culling uniform of both GPU culls: GpuCuller's (culling.wgsl) and the visibility
// strategy's (visibility_cull.wgsl, visibility_raster.wgsl). One struct, declared once for the
// shaders too (culling_view.wgsl's Culling), so that both test the same frustum and choose
// levels of detail from the same numbers; a few words at the end are each cull's own.

#include <array>
#include <cstddef>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "render/culling/LodSelection.h"

namespace encore::render {

struct CullingUniform {
    std::array<glm::vec4, 6> planes{};
    glm::mat4 viewProjection{1.0f};
    std::uint32_t lodViewCount = 0;
    float lodPixelsPerUnit = 0.0f;
    float lodThresholdPixels = 0.0f;
    std::uint32_t orthographic = 0;
    std::uint32_t occlusion = 0;
    float lodDistanceSlack = 0.0f;
    // GpuCuller's: the depth target, and where its lists and counts are.
    glm::vec2 viewport{0.0f};  // 8-byte aligned, as WGSL's vec2f.
    std::uint32_t phaseArguments = 0;
    std::uint32_t phaseVisible = 0;
    std::uint32_t trianglesDrawnWord = 0;
    std::uint32_t visibilityBase = 0;
    std::uint32_t levelBase = 0;
    // The visibility strategy's.
    std::uint32_t frustumTest = 0;
    std::uint32_t clusterCulling = 0;
    std::uint32_t worldSpheres = 0;
    std::uint32_t unitListBase = 0;
    std::array<std::uint32_t, 3> padding{};  // WGSL aligns lodViews to 16 bytes.
    std::array<glm::vec4, LodSelection::kMaxViews> lodViews{};
};
static_assert(offsetof(CullingUniform, lodViewCount) == 160);
static_assert(offsetof(CullingUniform, viewport) == 184);
static_assert(offsetof(CullingUniform, unitListBase) == 224);
static_assert(offsetof(CullingUniform, lodViews) == 240);
static_assert(sizeof(CullingUniform) == 496);

// What both culls write alike: the view-projection, the frustum's planes when `testFrustum`
// (otherwise planes nothing lies outside: a cull serving several views keeps what any sees),
// and the levels of detail of `lod`.
void fillCullingView(CullingUniform& uniform,
                     const glm::mat4& viewProjection,
                     bool testFrustum,
                     const LodSelection& lod);

}  // namespace encore::render
