#pragma once

// The closest hit of a ray in a TraceScene, on the CPU: what trace_bvh.wgsl does on the GPU,
// step for step, so that tests can compare the two and the hierarchies against brute force.

#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "trace/TraceScene.h"

namespace encore::trace {

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // Need not be normalised: t is in its units.
    float tMin = 0.0f;
    float tMax = 3.0e38f;
};

struct RayHit {
    float t = 0.0f;
    std::uint32_t object = 0;     // In TraceScene::objects.
    std::uint32_t triangle = 0;   // In TraceScene::triangles.
    glm::vec2 barycentric{0.0f};  // Of corners b and c; a's is 1 - x - y.
};

// The ray against one triangle (Moller-Trumbore, both faces): t, or none.
std::optional<RayHit> intersectTriangle(const Ray& ray, const TraceTriangle& triangle);

std::optional<RayHit> closestHit(const TraceScene& scene, const Ray& ray);

}  // namespace encore::trace
