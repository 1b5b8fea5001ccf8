#pragma once

#include <array>

#include "encore/scene/SceneData.h"

namespace encore::render {

// Attributes read by the transform-and-light shading of the strategies before `materials`.
inline constexpr std::array kUnlitTransformSemantics = {scene::Semantic::Position,
                                                        scene::Semantic::Normal};

}  // namespace encore::render
