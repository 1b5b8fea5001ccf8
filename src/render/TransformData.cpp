#include "render/TransformData.h"

#include <cstring>

#include <glm/gtc/type_ptr.hpp>

namespace encore::render {

TransformUniform makeTransformUniform(const scene::Instance& instance) {
    TransformUniform transform{};
    std::memcpy(transform.world, glm::value_ptr(instance.world), sizeof(transform.world));
    std::memcpy(transform.normal, glm::value_ptr(instance.normalMatrix), sizeof(transform.normal));
    // The normal matrix's fourth column never reaches a normal (w = 0): it carries the
    // segmentation ids, 1 + node and 1 + mesh index (exact in floats below 2^24; 0: none).
    transform.normal[12] = instance.node.valid() ? float(instance.node.index() + 1) : 0.0f;
    transform.normal[13] = instance.mesh.valid() ? float(instance.mesh.index() + 1) : 0.0f;
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
