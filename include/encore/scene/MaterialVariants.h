#pragma once

// KHR_materials_variants: a file names material variants ("midnight", "beach") and each
// primitive maps some of them to other materials (SceneData::variants,
// Primitive::variantMaterials). Selecting a variant (render::Renderer::selectVariant) changes
// which material each primitive draws, nothing else. These find a variant by name or index and
// read a file's variant names without loading it.

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "encore/core/Result.h"
#include "encore/scene/SceneData.h"

namespace encore::scene {

// The variant `nameOrIndex` names among `variants`: an exact name first, else a decimal index.
std::optional<VariantId> findVariant(std::span<const std::string> variants,
                                     std::string_view nameOrIndex);
std::optional<VariantId> findVariant(const SceneData& scene, std::string_view nameOrIndex);

// findVariant, or an InvalidArgument error that names `file` and lists the variants it has:
// "'shoe.glb' has no material variant 'red' (its variants: 0 'midnight', 1 'beach')."
Result<VariantId> resolveVariant(std::span<const std::string> variants,
                                 std::string_view nameOrIndex,
                                 const std::string& file);
Result<VariantId> resolveVariant(const SceneData& scene, std::string_view nameOrIndex);

// "0 'midnight', 1 'beach'", or "none".
std::string describeVariants(std::span<const std::string> variants);

// The variant names a .gltf or .glb declares, read from its JSON alone (not a .glb's binary
// chunk, not the buffers): what encore batch reads to know a model's samples before loading it.
// Errors name the file; a file that loads has the same names in SceneData::variants.
Result<std::vector<std::string>> readVariantNames(const std::filesystem::path& path);

}  // namespace encore::scene
