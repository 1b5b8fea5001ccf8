#pragma once

// A tiny asset with KHR_materials_variants for the tests of material variants: two quads facing
// +Z in one mesh, the left one (x in [-2, -0.2], y in [-1, 1]) mapped by every variant, the
// right one (x in [0.2, 2]) by none. Each variant reaches another part of the renderer: another
// factor, a blended material (the draw moves out of the opaque groups), a textured material
// with a normal map (other pipelines, and TANGENT bound).

#include <array>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "GltfBuilder.h"

namespace encore::test {

inline constexpr std::array<const char*, 4> kVariantNames = {"green", "blue paint", "glass",
                                                             "textured"};
// The left quad's base colour (linear, opaque) with no variant, then under each variant.
inline constexpr std::array<glm::vec3, 5> kLeftQuadColors = {
    glm::vec3(1.0f, 0.0f, 0.0f),  // Default: red.
    glm::vec3(0.0f, 1.0f, 0.0f),  // "green"
    glm::vec3(0.0f, 0.0f, 1.0f),  // "blue paint"
    glm::vec3(1.0f, 1.0f, 0.0f),  // "glass": BLEND with alpha 1, so exactly yellow.
    glm::vec3(1.0f, 0.0f, 1.0f),  // "textured": a white factor times a magenta texture.
};
inline constexpr glm::vec3 kRightQuadColor(0.5f, 0.5f, 0.5f);  // Under every variant.
inline constexpr glm::vec3 kLeftQuadCenter(-1.1f, 0.0f, 0.0f);
inline constexpr glm::vec3 kRightQuadCenter(1.1f, 0.0f, 0.0f);

GltfBuilder variantQuads();

}  // namespace encore::test
