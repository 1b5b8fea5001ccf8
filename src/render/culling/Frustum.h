#pragma once

#include <array>

#include <glm/glm.hpp>

#include "encore/scene/SceneData.h"

namespace encore::render {

// A bounding sphere: xyz centre, w radius.
using Sphere = glm::vec4;

// The six planes of a view-projection's frustum (WebGPU clip space, depth 0..1), each with an
// inward unit normal in xyz and its distance in w: left, right, bottom, top, near, far.
// Perspective and orthographic projections both work. An infinite perspective projection (and
// a far plane beyond 1e5 times the near distance) gets the far plane (0, 0, 0, 1), which keeps
// every sphere.
struct Frustum {
    std::array<glm::vec4, 6> planes;

    static Frustum fromViewProjection(const glm::mat4& viewProjection);
    // True unless the sphere lies entirely outside one plane (conservative, like the GPU test).
    bool intersects(const Sphere& sphere) const;
};

// The world-space sphere enclosing `bounds` (object space) transformed by `world`: the box's
// sphere, centre transformed, radius scaled by the largest axis scale.
Sphere worldSphere(const scene::Bounds& bounds, const glm::mat4& world);

}  // namespace encore::render
