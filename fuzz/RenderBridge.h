#pragma once

// The CPU-only functions of src/render that the prepare target calls, behind declarations
// free of WebGPU types: their headers include Dawn's webgpu_cpp.h, which clang 14 cannot
// parse, so RenderBridge.cpp is compiled by g++ (see CMakeLists.txt).

#include <cstddef>
#include <cstdint>
#include <optional>

#include "encore/scene/SceneData.h"

namespace encore::fuzz {

// render::shaderLocation(semantic).has_value(): whether a renderer binds the attribute.
bool bindsAttribute(scene::Semantic semantic);
// render::vertexFormat(accessor).has_value().
bool hasVertexFormat(const scene::Accessor& accessor);
// render::indexFormat(accessor) is Uint16 or Uint32.
bool hasIndexFormat(const scene::Accessor& accessor);
// render::paddedVertexElements: its size in bytes, and the stride it chose.
std::size_t paddedVertexBytes(const scene::SceneData& scene,
                              scene::AccessorId accessor,
                              std::uint32_t& stride);
// render::makeMaterialUniform plus the shader-variant questions, folded into one number.
float materialUniformChecksum(const scene::Material& material);
// render::kMaterialTextureSlotCount, and render::slotTexture for each slot.
std::uint32_t materialSlotCount();
std::optional<scene::TextureRef> materialSlotTexture(const scene::Material& material,
                                                     std::uint32_t slot);
// The sampler's WebGPU modes (render::filterMode, mipmapFilterMode, addressMode), folded.
std::uint32_t samplerChecksum(const scene::Sampler& sampler);

}  // namespace encore::fuzz
