#pragma once

// The triangles a primitive draws, as vertex indices: what the CPU's readers of surfaces (point
// clouds, ray tracing's hierarchies) walk.

#include <cstdint>
#include <vector>

#include "encore/scene/SceneData.h"

namespace encore::scene {

// Three vertex indices per triangle, in the order drawn: a list's as they are, a strip's
// unrolled with every other triangle's winding turned back; none for points and lines.
std::vector<std::uint32_t> triangleCorners(const SceneData& scene, const Primitive& primitive);

}  // namespace encore::scene
