#pragma once

#include <array>

#include "encore/scene/SceneData.h"

namespace encore::render {

// Attributes read by the transform-and-light shading of the strategies before `materials`.
inline constexpr std::array kUnlitTransformSemantics = {scene::Semantic::Position,
                                                        scene::Semantic::Normal};

// Attributes read by the material shading (absent ones select a shader variant).
inline constexpr std::array kMaterialSemantics = {scene::Semantic::Position,
                                                  scene::Semantic::Normal,
                                                  scene::Semantic::Texcoord0,
                                                  scene::Semantic::Color0};

}  // namespace encore::render
