// Materials, textures and samplers: parsed from JSON, then mapped to SceneData's types. A texture
// without a sampler gets the glTF default sampler, appended once; a primitive without a material
// gets the glTF default material, appended once. The material extensions are read, converted and
// listed by MaterialExtensionParser.cpp.

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include "scene/LoadContext.h"
#include "scene/MaterialExtensionParser.h"

namespace encore::scene {
namespace {

constexpr std::uint64_t kGlNearest = 9728;
constexpr std::uint64_t kGlLinear = 9729;
constexpr std::uint64_t kGlNearestMipmapNearest = 9984;
constexpr std::uint64_t kGlLinearMipmapNearest = 9985;
constexpr std::uint64_t kGlNearestMipmapLinear = 9986;
constexpr std::uint64_t kGlLinearMipmapLinear = 9987;
constexpr std::uint64_t kGlClampToEdge = 33071;
constexpr std::uint64_t kGlMirroredRepeat = 33648;
constexpr std::uint64_t kGlRepeat = 10497;

Result<Sampler> toSampler(const GltfSampler& source, std::size_t index) {
    Sampler sampler;
    const std::string name = "sampler " + std::to_string(index);
    if (source.magFilter) {
        if (*source.magFilter != kGlNearest && *source.magFilter != kGlLinear) {
            return makeError(
                ErrorCode::InvalidFormat,
                name + " has an invalid magFilter (" + std::to_string(*source.magFilter) + ").");
        }
        sampler.magFilter = *source.magFilter == kGlNearest ? Filter::Nearest : Filter::Linear;
    }
    if (source.minFilter) {
        switch (*source.minFilter) {
            case kGlNearest:
            case kGlLinear:
                sampler.useMipmaps = false;
                sampler.minFilter =
                    *source.minFilter == kGlNearest ? Filter::Nearest : Filter::Linear;
                break;
            case kGlNearestMipmapNearest:
            case kGlLinearMipmapNearest:
            case kGlNearestMipmapLinear:
            case kGlLinearMipmapLinear:
                sampler.minFilter = (*source.minFilter == kGlNearestMipmapNearest ||
                                     *source.minFilter == kGlNearestMipmapLinear)
                                        ? Filter::Nearest
                                        : Filter::Linear;
                sampler.mipmapFilter =
                    *source.minFilter <= kGlLinearMipmapNearest ? Filter::Nearest : Filter::Linear;
                break;
            default:
                return makeError(ErrorCode::InvalidFormat, name + " has an invalid minFilter (" +
                                                               std::to_string(*source.minFilter) +
                                                               ").");
        }
    }
    for (auto [value, wrap, key] : {std::tuple{source.wrapS, &sampler.wrapS, "wrapS"},
                                    std::tuple{source.wrapT, &sampler.wrapT, "wrapT"}}) {
        if (value == kGlClampToEdge) {
            *wrap = Wrap::ClampToEdge;
        } else if (value == kGlMirroredRepeat) {
            *wrap = Wrap::MirroredRepeat;
        } else if (value == kGlRepeat) {
            *wrap = Wrap::Repeat;
        } else {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has an invalid " + key + " (" + std::to_string(value) + ").");
        }
    }
    return sampler;
}

}  // namespace

std::optional<GltfTextureInfo> readTextureInfo(FieldReader& parent,
                                               const Json* object,
                                               std::string_view slot,
                                               std::string_view scaleKey) {
    if (!object) {
        return std::nullopt;
    }
    FieldReader reader(*object, parent.element() + " " + std::string(slot));
    GltfTextureInfo info;
    info.index = reader.requiredIndex("index");
    info.texCoord = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(reader.uint("texCoord", 0), 0xFFFFFFFFu));
    if (!scaleKey.empty()) {
        info.scale = float(reader.number(scaleKey, 1.0));
    }
    if (const Json* transform = extensionObject(reader, "KHR_texture_transform")) {
        FieldReader fields(*transform, reader.element() + " KHR_texture_transform");
        TextureTransform result;
        if (const auto offset = fields.numbers("offset", 2); offset.size() == 2) {
            result.offset = glm::vec2(offset[0], offset[1]);
        }
        result.rotation = float(fields.number("rotation", 0.0));
        if (const auto scale = fields.numbers("scale", 2); scale.size() == 2) {
            result.scale = glm::vec2(scale[0], scale[1]);
        }
        // The extension may override the texCoord set the transformed coordinates come from.
        if (const auto texCoord = fields.optionalUint("texCoord")) {
            info.texCoord = static_cast<std::uint32_t>(std::min<std::uint64_t>(*texCoord, 255));
        }
        info.transform = result;
        if (fields.failed()) {
            reader.fail(fields.error().code, fields.error().message);
        }
    }
    if (reader.failed()) {
        parent.fail(reader.error().code, reader.error().message);
    }
    return info;
}

std::optional<TextureRef> toTextureRef(const std::optional<GltfTextureInfo>& info) {
    if (!info) {
        return std::nullopt;
    }
    return TextureRef{TextureId(info->index), info->texCoord, info->transform};
}

Result<void> parseMaterialElements(const Json& root, GltfDocument& document) {
    ENCORE_TRY(forEachElement(root, "materials", "material", [&](FieldReader& reader, std::size_t) {
        GltfMaterial material;
        material.name = reader.string("name");
        if (const Json* pbr = reader.object("pbrMetallicRoughness")) {
            FieldReader fields(*pbr, reader.element() + " pbrMetallicRoughness");
            if (const auto color = fields.numbers("baseColorFactor", 4); color.size() == 4) {
                material.baseColorFactor = glm::vec4(color[0], color[1], color[2], color[3]);
            }
            material.baseColorTexture =
                readTextureInfo(reader, fields.object("baseColorTexture"), "baseColorTexture", {});
            material.metallicFactor = float(fields.number("metallicFactor", 1.0));
            material.roughnessFactor = float(fields.number("roughnessFactor", 1.0));
            material.metallicRoughnessTexture = readTextureInfo(
                reader, fields.object("metallicRoughnessTexture"), "metallicRoughnessTexture", {});
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        material.normalTexture =
            readTextureInfo(reader, reader.object("normalTexture"), "normalTexture", "scale");
        material.occlusionTexture = readTextureInfo(reader, reader.object("occlusionTexture"),
                                                    "occlusionTexture", "strength");
        material.emissiveTexture =
            readTextureInfo(reader, reader.object("emissiveTexture"), "emissiveTexture", {});
        if (const auto emissive = reader.numbers("emissiveFactor", 3); emissive.size() == 3) {
            material.emissiveFactor = glm::vec3(emissive[0], emissive[1], emissive[2]);
        }
        material.alphaMode = reader.string("alphaMode", "OPAQUE");
        material.alphaCutoff = float(reader.number("alphaCutoff", 0.5));
        material.doubleSided = reader.boolean("doubleSided", false);
        readMaterialExtensions(reader, material);
        if (!reader.failed() && material.alphaMode != "OPAQUE" && material.alphaMode != "MASK" &&
            material.alphaMode != "BLEND") {
            reader.fail(
                ErrorCode::InvalidFormat,
                reader.element() + " has an unknown alphaMode ('" + material.alphaMode + "').");
        }
        document.materials.push_back(std::move(material));
    }));
    ENCORE_TRY(forEachElement(root, "textures", "texture", [&](FieldReader& reader, std::size_t) {
        GltfTexture texture;
        texture.source = reader.optionalIndex("source");
        texture.sampler = reader.optionalIndex("sampler");
        // Alternative images: a WebP one Encore decodes, a KTX2 one it cannot.
        for (auto [name, source] : {std::pair{"EXT_texture_webp", &texture.webpSource},
                                    std::pair{"KHR_texture_basisu", &texture.basisuSource}}) {
            if (const Json* extension = extensionObject(reader, name)) {
                FieldReader fields(*extension, reader.element() + " " + name);
                *source = fields.requiredIndex("source");
                if (fields.failed()) {
                    reader.fail(fields.error().code, fields.error().message);
                }
            }
        }
        document.textures.push_back(texture);
    }));
    ENCORE_TRY(forEachElement(root, "images", "image", [&](FieldReader& reader, std::size_t) {
        GltfImage image;
        image.name = reader.string("name");
        image.uri = reader.optionalString("uri");
        image.bufferView = reader.optionalIndex("bufferView");
        image.mimeType = reader.string("mimeType");
        document.images.push_back(std::move(image));
    }));
    return forEachElement(root, "samplers", "sampler", [&](FieldReader& reader, std::size_t) {
        GltfSampler sampler;
        sampler.magFilter = reader.optionalUint("magFilter");
        sampler.minFilter = reader.optionalUint("minFilter");
        sampler.wrapS = reader.uint("wrapS", kGlRepeat);
        sampler.wrapT = reader.uint("wrapT", kGlRepeat);
        document.samplers.push_back(sampler);
    });
}

Result<void> convertMaterials(LoadContext& context) {
    const GltfDocument& document = context.document;
    SceneData& scene = context.scene;
    scene.variants = document.variants;  // KHR_materials_variants; convertMeshes maps them.
    for (std::size_t i = 0; i < document.samplers.size(); ++i) {
        Sampler sampler;
        ENCORE_TRY_ASSIGN(sampler, toSampler(document.samplers[i], i));
        scene.samplers.push_back(sampler);
    }
    std::optional<SamplerId> defaultSampler;
    for (std::size_t t = 0; t < document.textures.size(); ++t) {
        const GltfTexture& source = document.textures[t];
        Texture texture;
        // loadImages chose between EXT_texture_webp's image and the core source.
        if (const std::optional<std::uint32_t> drawn = context.textureImages[t]) {
            texture.image = ImageId(*drawn);
        }
        if (source.basisuSource) {
            texture.basisuImage = ImageId(*source.basisuSource);
        }
        if (source.sampler) {
            texture.sampler = SamplerId(*source.sampler);
        } else {
            if (!defaultSampler) {
                defaultSampler = SamplerId(scene.samplers.size());
                scene.samplers.push_back(Sampler{});
            }
            texture.sampler = *defaultSampler;
        }
        scene.textures.push_back(texture);
    }
    for (const GltfMaterial& source : document.materials) {
        Material material;
        material.name = source.name;
        material.baseColorFactor = source.baseColorFactor;
        material.baseColorTexture = toTextureRef(source.baseColorTexture);
        material.metallicFactor = source.metallicFactor;
        material.roughnessFactor = source.roughnessFactor;
        material.metallicRoughnessTexture = toTextureRef(source.metallicRoughnessTexture);
        material.normalTexture = toTextureRef(source.normalTexture);
        material.occlusionTexture = toTextureRef(source.occlusionTexture);
        material.emissiveTexture = toTextureRef(source.emissiveTexture);
        material.emissiveFactor = source.emissiveFactor;
        material.alphaMode = source.alphaMode == "MASK"    ? AlphaMode::Mask
                             : source.alphaMode == "BLEND" ? AlphaMode::Blend
                                                           : AlphaMode::Opaque;
        material.alphaCutoff = source.alphaCutoff;
        material.doubleSided = source.doubleSided;
        if (source.normalTexture) {
            material.normalScale = source.normalTexture->scale;
        }
        if (source.occlusionTexture) {
            material.occlusionStrength = source.occlusionTexture->scale;
        }
        material.emissiveStrength = source.emissiveStrength;
        material.unlit = source.unlit;
        material.ior = source.ior;
        convertMaterialExtensions(source, material);
        material.ignoredExtensions = source.ignoredExtensions;
        scene.materials.push_back(std::move(material));
    }
    return {};
}

std::vector<GltfMaterialTextureSlot> materialTextureSlots(const GltfMaterial& material) {
    std::vector<GltfMaterialTextureSlot> slots;
    auto add = [&slots](std::string slot, const std::optional<GltfTextureInfo>& info) {
        if (info) {
            slots.push_back({std::move(slot), &*info});
        }
    };
    add("baseColorTexture", material.baseColorTexture);
    add("metallicRoughnessTexture", material.metallicRoughnessTexture);
    add("normalTexture", material.normalTexture);
    add("occlusionTexture", material.occlusionTexture);
    add("emissiveTexture", material.emissiveTexture);
    addExtensionTextureSlots(material, slots);
    return slots;
}

MaterialId defaultMaterial(SceneData& scene) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (scene.materials[i].isDefault) {
            return MaterialId(i);
        }
    }
    Material material;
    material.name = "glTF default material";
    material.isDefault = true;
    scene.materials.push_back(std::move(material));
    return MaterialId(scene.materials.size() - 1);
}

}  // namespace encore::scene
