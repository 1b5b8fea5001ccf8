#pragma once

#include <cmath>
#include <limits>

#include <glm/glm.hpp>

namespace encore::scene {

// An axis-aligned box; empty until a point is added. Points with a NaN or infinite coordinate
// are ignored, so a box is either empty or finite.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const glm::vec3& point) {
        if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) {
            return;
        }
        min = glm::min(min, point);
        max = glm::max(max, point);
    }
    void extend(const Bounds& other) {
        if (!other.empty()) {
            extend(other.min);
            extend(other.max);
        }
    }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    // Radius of the sphere around center() that encloses the box.
    float radius() const { return empty() ? 0.0f : glm::length(max - min) * 0.5f; }

    // The box enclosing this box's eight corners after an affine transform.
    Bounds transformed(const glm::mat4& transform) const {
        Bounds result;
        if (empty()) {
            return result;
        }
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 point((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y,
                                  (corner & 4) ? max.z : min.z);
            result.extend(glm::vec3(transform * glm::vec4(point, 1.0f)));
        }
        return result;
    }
};

}  // namespace encore::scene
