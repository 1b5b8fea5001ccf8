#pragma once

#include "encore/render/BindGroupLayouts.h"
#include "encore/scene/SceneData.h"

namespace encore::render {

// The GPU form of an instance's world and normal matrices.
TransformUniform makeTransformUniform(const scene::Instance& instance);

}  // namespace encore::render
