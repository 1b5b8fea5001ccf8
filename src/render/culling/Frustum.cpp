#include "render/culling/Frustum.h"

#include <algorithm>

namespace encore::render {

namespace {
constexpr float kNoFarPlaneRatio = 1e-5f;
}  // namespace

Frustum Frustum::fromViewProjection(const glm::mat4& m) {
    // Gribb and Hartmann: planes from sums of the matrix rows (glm stores columns).
    auto row = [&](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    Frustum frustum;
    frustum.planes = {row(3) + row(0), row(3) - row(0), row(3) + row(1),
                      row(3) - row(1), row(2),          row(3) - row(2)};
    // An infinite perspective projection has no far plane: row 3 - row 2 loses its normal
    // (exactly, or to the kInfiniteDepthScale of Camera.h) and normalising it would divide by
    // zero or leave a plane made of rounding errors. A far plane whose normal is that small
    // against the near plane's (a far plane beyond 1e5 near-plane distances) becomes the plane
    // that passes everything: culling less than possible is safe, the rasterizer still clips.
    const float nearNormal = glm::length(glm::vec3(frustum.planes[4]));
    const float farNormal = glm::length(glm::vec3(frustum.planes[5]));
    if (!(farNormal > kNoFarPlaneRatio * nearNormal)) {
        frustum.planes[5] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    }
    for (glm::vec4& plane : frustum.planes) {
        const float length = glm::length(glm::vec3(plane));
        if (length > 0.0f) {
            plane /= length;
        }
    }
    return frustum;
}

bool Frustum::intersects(const Sphere& sphere) const {
    for (const glm::vec4& plane : planes) {
        if (glm::dot(glm::vec3(plane), glm::vec3(sphere)) + plane.w < -sphere.w) {
            return false;
        }
    }
    return true;
}

Sphere worldSphere(const scene::Bounds& bounds, const glm::mat4& world) {
    if (bounds.empty()) {
        return Sphere(glm::vec3(world[3]), 0.0f);
    }
    const glm::vec3 center = glm::vec3(world * glm::vec4(bounds.center(), 1.0f));
    const float scale =
        std::max({glm::length(glm::vec3(world[0])), glm::length(glm::vec3(world[1])),
                  glm::length(glm::vec3(world[2]))});
    return Sphere(center, bounds.radius() * scale);
}

}  // namespace encore::render
