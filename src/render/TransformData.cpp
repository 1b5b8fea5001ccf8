#include "render/TransformData.h"

#include <cstring>

#include <glm/gtc/type_ptr.hpp>

namespace encore::render {

TransformUniform makeTransformUniform(const scene::Instance& instance) {
    TransformUniform transform{};
    std::memcpy(transform.world, glm::value_ptr(instance.world), sizeof(transform.world));
    std::memcpy(transform.normal, glm::value_ptr(instance.normalMatrix), sizeof(transform.normal));
    return transform;
}

TransformUniform makeTransformUniform(const glm::mat4& world) {
    scene::Instance instance;
    instance.world = world;
    instance.normalMatrix = normalMatrixOf(world);
    return makeTransformUniform(instance);
}

glm::mat4 normalMatrixOf(const glm::mat4& world) {
    return scene::normalMatrixOf(world);  // Finite even for singular or non-finite matrices.
}

}  // namespace encore::render
