#include "encore/render/TransformData.h"

#include <cstring>

#include <glm/gtc/type_ptr.hpp>

namespace encore::render {

TransformUniform makeTransformUniform(const scene::Instance& instance) {
    TransformUniform transform{};
    std::memcpy(transform.world, glm::value_ptr(instance.world), sizeof(transform.world));
    std::memcpy(transform.normal, glm::value_ptr(instance.normalMatrix), sizeof(transform.normal));
    return transform;
}

}  // namespace encore::render
