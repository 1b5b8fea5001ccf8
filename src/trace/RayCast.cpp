#include "trace/RayCast.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace encore::trace {
namespace {

// Deeper than any hierarchy Embree builds (maxDepth 64), so the stack cannot overflow.
constexpr std::size_t kStackSize = 64;

// The ray's entry distance into the box, or none when it misses it within [tMin, tMax].
std::optional<float> enterBox(const BvhNode& node,
                              const glm::vec3& origin,
                              const glm::vec3& inverseDirection,
                              float tMin,
                              float tMax) {
    const glm::vec3 t0 = (node.min - origin) * inverseDirection;
    const glm::vec3 t1 = (node.max - origin) * inverseDirection;
    const glm::vec3 near = glm::min(t0, t1);
    const glm::vec3 far = glm::max(t0, t1);
    const float enter = std::max({near.x, near.y, near.z, tMin});
    const float exit = std::min({far.x, far.y, far.z, tMax});
    if (enter > exit) {
        return std::nullopt;
    }
    return enter;
}

// Visits the leaves of `nodes` from `root` whose boxes the ray enters before `ray.tMax`,
// nearer child first; `leaf(node)` may shorten ray.tMax.
template <typename Leaf>
void traverse(const std::vector<BvhNode>& nodes, std::uint32_t root, Ray& ray, Leaf&& leaf) {
    const glm::vec3 inverse = 1.0f / ray.direction;
    std::array<std::uint32_t, kStackSize> stack;
    std::size_t size = 0;
    if (!enterBox(nodes[root], ray.origin, inverse, ray.tMin, ray.tMax)) {
        return;
    }
    stack[size++] = root;
    while (size > 0) {
        const BvhNode& node = nodes[stack[--size]];
        if (node.leaf()) {
            leaf(node);
            continue;
        }
        const auto near = enterBox(nodes[node.first], ray.origin, inverse, ray.tMin, ray.tMax);
        const auto far = enterBox(nodes[node.first + 1], ray.origin, inverse, ray.tMin, ray.tMax);
        if (near && far) {
            const bool firstNearer = *near <= *far;
            stack[size++] = firstNearer ? node.first + 1 : node.first;
            stack[size++] = firstNearer ? node.first : node.first + 1;
        } else if (near) {
            stack[size++] = node.first;
        } else if (far) {
            stack[size++] = node.first + 1;
        }
    }
}

}  // namespace

std::optional<RayHit> intersectTriangle(const Ray& ray, const TraceTriangle& triangle) {
    const glm::vec3 edge1 = triangle.b - triangle.a;
    const glm::vec3 edge2 = triangle.c - triangle.a;
    const glm::vec3 p = glm::cross(ray.direction, edge2);
    const float determinant = glm::dot(edge1, p);
    if (determinant == 0.0f || !std::isfinite(determinant)) {
        return std::nullopt;  // Parallel to the plane, or degenerate.
    }
    const float inverse = 1.0f / determinant;
    const glm::vec3 s = ray.origin - triangle.a;
    const float u = glm::dot(s, p) * inverse;
    if (u < 0.0f || u > 1.0f) {
        return std::nullopt;
    }
    const glm::vec3 q = glm::cross(s, edge1);
    const float v = glm::dot(ray.direction, q) * inverse;
    if (v < 0.0f || u + v > 1.0f) {
        return std::nullopt;
    }
    const float t = glm::dot(edge2, q) * inverse;
    if (!(t > ray.tMin && t < ray.tMax)) {
        return std::nullopt;
    }
    return RayHit{t, 0, 0, {u, v}};
}

std::optional<RayHit> closestHit(const TraceScene& scene, const Ray& worldRay) {
    if (scene.objectNodes.empty()) {
        return std::nullopt;
    }
    std::optional<RayHit> closest;
    Ray ray = worldRay;
    traverse(scene.objectNodes, 0, ray, [&](const BvhNode& leaf) {
        for (std::uint32_t o = leaf.first; o < leaf.first + leaf.count; ++o) {
            const TraceObject& object = scene.objects[o];
            // The object's space keeps t: the direction is transformed, not normalised.
            Ray local{glm::vec3(object.worldToObject * glm::vec4(ray.origin, 1.0f)),
                      glm::vec3(object.worldToObject * glm::vec4(ray.direction, 0.0f)), ray.tMin,
                      ray.tMax};
            traverse(scene.meshNodes, object.root, local, [&](const BvhNode& triangles) {
                for (std::uint32_t t = triangles.first; t < triangles.first + triangles.count;
                     ++t) {
                    if (auto hit = intersectTriangle(local, scene.triangles[t])) {
                        hit->object = o;
                        hit->triangle = t;
                        local.tMax = hit->t;
                        closest = hit;
                    }
                }
            });
            ray.tMax = local.tMax;
        }
    });
    return closest;
}

}  // namespace encore::trace
