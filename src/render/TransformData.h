#pragma once

#include "encore/scene/SceneData.h"
#include "render/BindGroupLayouts.h"

namespace encore::render {

// The GPU form of an instance's world and normal matrices, and its segmentation ids (the normal
// matrix's fourth column, 0 without an instance).
TransformUniform makeTransformUniform(const scene::Instance& instance);
TransformUniform makeTransformUniform(const glm::mat4& world);

// The bytes of a TransformUniform that a new world matrix changes: all but the segmentation ids
// at its end, which updates keep.
inline constexpr std::uint64_t kTransformMatricesSize =
    sizeof(TransformUniform) - 4 * sizeof(float);

// The inverse transpose of the upper 3x3 of `world`, in a mat4 (how normals transform); always
// finite (scene::normalMatrixOf says what singular matrices get).
glm::mat4 normalMatrixOf(const glm::mat4& world);

}  // namespace encore::render
