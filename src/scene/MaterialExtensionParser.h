#pragma once

// The material extensions Encore shades (kShadedMaterialExtensions): read from a material's
// `extensions` object into GltfMaterial, copied into scene::Material, and their textures listed
// for validation. MaterialParser.cpp calls these for each material; a new extension is added
// here (docs/adding-a-material-extension.md).

#include <optional>
#include <string_view>
#include <vector>

#include "scene/GltfDocument.h"

namespace encore::scene {

// MaterialParser.cpp: a textureInfo object (nullopt when `object` is null), with its
// KHR_texture_transform; `slot` names it in messages, `scaleKey` is read into `scale` when not
// empty ("scale", "strength"). Errors go to `parent`.
std::optional<GltfTextureInfo> readTextureInfo(FieldReader& parent,
                                               const Json* object,
                                               std::string_view slot,
                                               std::string_view scaleKey);
// MaterialParser.cpp: the scene's texture reference for a parsed textureInfo.
std::optional<TextureRef> toTextureRef(const std::optional<GltfTextureInfo>& info);

// Reads the material's extensions object (if any) into `material`: shaded extensions into their
// structs, other names into ignoredExtensions. An invalid value is an error sentence naming the
// material, the extension, the field and the value, recorded in `reader`.
void readMaterialExtensions(FieldReader& reader, GltfMaterial& material);

// Copies the extensions of `source` into `material`, whose core fields are already set
// (KHR_materials_pbrSpecularGlossiness replaces its base colour).
void convertMaterialExtensions(const GltfMaterial& source, Material& material);

// Appends the texture references of the material's extensions, named as messages name them
// ("KHR_materials_clearcoat clearcoatTexture").
void addExtensionTextureSlots(const GltfMaterial& material,
                              std::vector<GltfMaterialTextureSlot>& slots);

}  // namespace encore::scene
