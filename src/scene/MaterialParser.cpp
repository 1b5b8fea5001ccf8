// Materials, textures and samplers: parsed from JSON, then mapped to SceneData's types. A texture
// without a sampler gets the glTF default sampler, appended once; a primitive without a material
// gets the glTF default material, appended once. Material extensions Encore shades are read into
// their structs; other extension objects on a material are only named (ignoredExtensions), so
// the base material is drawn and the user can be told what was left out.

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include "scene/LoadContext.h"

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

glm::vec3 readVec3(FieldReader& reader, std::string_view key, glm::vec3 fallback) {
    if (const auto values = reader.numbers(key, 3); values.size() == 3) {
        return glm::vec3(values[0], values[1], values[2]);
    }
    return fallback;
}

GltfSpecular readSpecular(FieldReader& fields) {
    GltfSpecular specular;
    specular.specularFactor = float(fields.number("specularFactor", 1.0));
    specular.specularTexture =
        readTextureInfo(fields, fields.object("specularTexture"), "specularTexture", {});
    specular.specularColorFactor = readVec3(fields, "specularColorFactor", glm::vec3(1.0f));
    specular.specularColorTexture =
        readTextureInfo(fields, fields.object("specularColorTexture"), "specularColorTexture", {});
    return specular;
}

GltfClearcoat readClearcoat(FieldReader& fields) {
    GltfClearcoat clearcoat;
    clearcoat.clearcoatFactor = float(fields.number("clearcoatFactor", 0.0));
    clearcoat.clearcoatTexture =
        readTextureInfo(fields, fields.object("clearcoatTexture"), "clearcoatTexture", {});
    clearcoat.clearcoatRoughnessFactor = float(fields.number("clearcoatRoughnessFactor", 0.0));
    clearcoat.clearcoatRoughnessTexture = readTextureInfo(
        fields, fields.object("clearcoatRoughnessTexture"), "clearcoatRoughnessTexture", {});
    clearcoat.clearcoatNormalTexture = readTextureInfo(
        fields, fields.object("clearcoatNormalTexture"), "clearcoatNormalTexture", "scale");
    return clearcoat;
}

GltfSheen readSheen(FieldReader& fields) {
    GltfSheen sheen;
    sheen.sheenColorFactor = readVec3(fields, "sheenColorFactor", glm::vec3(0.0f));
    sheen.sheenColorTexture =
        readTextureInfo(fields, fields.object("sheenColorTexture"), "sheenColorTexture", {});
    sheen.sheenRoughnessFactor = float(fields.number("sheenRoughnessFactor", 0.0));
    sheen.sheenRoughnessTexture = readTextureInfo(fields, fields.object("sheenRoughnessTexture"),
                                                  "sheenRoughnessTexture", {});
    return sheen;
}

GltfSpecularGlossiness readSpecularGlossiness(FieldReader& fields) {
    GltfSpecularGlossiness result;
    if (const auto diffuse = fields.numbers("diffuseFactor", 4); diffuse.size() == 4) {
        result.diffuseFactor = glm::vec4(diffuse[0], diffuse[1], diffuse[2], diffuse[3]);
    }
    result.diffuseTexture =
        readTextureInfo(fields, fields.object("diffuseTexture"), "diffuseTexture", {});
    result.specularFactor = readVec3(fields, "specularFactor", glm::vec3(1.0f));
    result.glossinessFactor = float(fields.number("glossinessFactor", 1.0));
    result.specularGlossinessTexture = readTextureInfo(
        fields, fields.object("specularGlossinessTexture"), "specularGlossinessTexture", {});
    return result;
}

// A factor that must lie in [minimum, maximum] (maximum < 0: no upper bound); an error names the
// field and the value otherwise.
float boundedNumber(FieldReader& fields,
                    std::string_view key,
                    double fallback,
                    double minimum,
                    double maximum) {
    const double value = fields.number(key, fallback);
    if (value < minimum || (maximum >= minimum && value > maximum)) {
        const std::string range =
            maximum >= minimum
                ? "it must lie in [" + formatNumber(minimum) + ", " + formatNumber(maximum) + "]"
                : "it must be at least " + formatNumber(minimum);
        fields.fail(ErrorCode::InvalidFormat, fields.element() + " has an invalid " +
                                                  std::string(key) + " (" + formatNumber(value) +
                                                  "; " + range + ").");
    }
    return float(value);
}

GltfIridescence readIridescence(FieldReader& fields) {
    GltfIridescence iridescence;
    iridescence.iridescenceFactor = boundedNumber(fields, "iridescenceFactor", 0.0, 0.0, 1.0);
    iridescence.iridescenceTexture =
        readTextureInfo(fields, fields.object("iridescenceTexture"), "iridescenceTexture", {});
    iridescence.iridescenceIor = boundedNumber(fields, "iridescenceIor", 1.3, 1.0, -1.0);
    iridescence.iridescenceThicknessMinimum =
        boundedNumber(fields, "iridescenceThicknessMinimum", 100.0, 0.0, -1.0);
    iridescence.iridescenceThicknessMaximum =
        boundedNumber(fields, "iridescenceThicknessMaximum", 400.0, 0.0, -1.0);
    iridescence.iridescenceThicknessTexture = readTextureInfo(
        fields, fields.object("iridescenceThicknessTexture"), "iridescenceThicknessTexture", {});
    return iridescence;
}

GltfAnisotropy readAnisotropy(FieldReader& fields) {
    GltfAnisotropy anisotropy;
    anisotropy.anisotropyStrength = boundedNumber(fields, "anisotropyStrength", 0.0, 0.0, 1.0);
    anisotropy.anisotropyRotation = float(fields.number("anisotropyRotation", 0.0));
    anisotropy.anisotropyTexture =
        readTextureInfo(fields, fields.object("anisotropyTexture"), "anisotropyTexture", {});
    return anisotropy;
}

GltfTransmission readTransmission(FieldReader& fields) {
    GltfTransmission transmission;
    transmission.transmissionFactor = boundedNumber(fields, "transmissionFactor", 0.0, 0.0, 1.0);
    transmission.transmissionTexture =
        readTextureInfo(fields, fields.object("transmissionTexture"), "transmissionTexture", {});
    return transmission;
}

GltfVolume readVolume(FieldReader& fields) {
    GltfVolume volume;
    volume.thicknessFactor = boundedNumber(fields, "thicknessFactor", 0.0, 0.0, -1.0);
    volume.thicknessTexture =
        readTextureInfo(fields, fields.object("thicknessTexture"), "thicknessTexture", {});
    if (fields.has("attenuationDistance")) {
        const double distance = fields.number("attenuationDistance", 0.0);
        if (!(distance > 0.0)) {
            fields.fail(ErrorCode::InvalidFormat,
                        fields.element() + " has an invalid attenuationDistance (" +
                            formatNumber(distance) + "; it must be greater than 0).");
        }
        volume.attenuationDistance = float(distance);
    }
    volume.attenuationColor = readVec3(fields, "attenuationColor", glm::vec3(1.0f));
    for (int channel = 0; channel < 3; ++channel) {
        const float value = volume.attenuationColor[channel];
        if (value < 0.0f || value > 1.0f) {
            fields.fail(ErrorCode::InvalidFormat,
                        fields.element() + " has an invalid attenuationColor (component " +
                            std::to_string(channel) + " is " + formatNumber(value) +
                            "; each must be between 0 and 1).");
            break;
        }
    }
    return volume;
}

// Reads the material's extensions object into `material`; errors go to `reader`.
void readMaterialExtensions(FieldReader& reader, GltfMaterial& material) {
    const Json* extensions = reader.object("extensions");
    if (!extensions) {
        return;
    }
    for (const auto& [name, value] : extensions->items()) {
        if (reader.failed()) {
            return;
        }
        if (std::find(kShadedMaterialExtensions.begin(), kShadedMaterialExtensions.end(), name) ==
            kShadedMaterialExtensions.end()) {
            material.ignoredExtensions.push_back(name);
            continue;
        }
        if (!value.is_object()) {
            reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an invalid " + name +
                                                      " extension (expected an object, got " +
                                                      describeJson(value) + ").");
            return;
        }
        FieldReader fields(value, reader.element() + " " + name);
        if (name == "KHR_materials_emissive_strength") {
            const double strength = fields.number("emissiveStrength", 1.0);
            if (strength < 0.0) {
                fields.fail(ErrorCode::InvalidFormat,
                            fields.element() + " has an invalid emissiveStrength (" +
                                formatNumber(strength) + "; it must not be negative).");
            }
            material.emissiveStrength = float(strength);
        } else if (name == "KHR_materials_unlit") {
            material.unlit = true;
        } else if (name == "KHR_materials_ior") {
            const double ior = fields.number("ior", 1.5);
            // 0 stands for an infinite index of refraction; values between 0 and 1 have no
            // physical meaning and the extension forbids them.
            if (ior != 0.0 && ior < 1.0) {
                fields.fail(ErrorCode::InvalidFormat, fields.element() + " has an invalid ior (" +
                                                          formatNumber(ior) +
                                                          "; it must be 0 or at least 1).");
            }
            material.ior = float(ior);
        } else if (name == "KHR_materials_specular") {
            material.specular = readSpecular(fields);
        } else if (name == "KHR_materials_clearcoat") {
            material.clearcoat = readClearcoat(fields);
        } else if (name == "KHR_materials_sheen") {
            material.sheen = readSheen(fields);
        } else if (name == "KHR_materials_pbrSpecularGlossiness") {
            material.specularGlossiness = readSpecularGlossiness(fields);
        } else if (name == "KHR_materials_iridescence") {
            material.iridescence = readIridescence(fields);
        } else if (name == "KHR_materials_anisotropy") {
            material.anisotropy = readAnisotropy(fields);
        } else if (name == "KHR_materials_transmission") {
            material.transmission = readTransmission(fields);
        } else if (name == "KHR_materials_volume") {
            material.volume = readVolume(fields);
        } else if (name == "KHR_materials_dispersion") {
            material.dispersion = boundedNumber(fields, "dispersion", 0.0, 0.0, -1.0);
        }
        if (fields.failed()) {
            reader.fail(fields.error().code, fields.error().message);
        }
    }
}

std::optional<TextureRef> toTextureRef(const std::optional<GltfTextureInfo>& info) {
    if (!info) {
        return std::nullopt;
    }
    return TextureRef{TextureId(info->index), info->texCoord, info->transform};
}

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
        if (const auto& specular = source.specular) {
            material.specular = SpecularExtension{
                .specularFactor = specular->specularFactor,
                .specularTexture = toTextureRef(specular->specularTexture),
                .specularColorFactor = specular->specularColorFactor,
                .specularColorTexture = toTextureRef(specular->specularColorTexture),
            };
        }
        if (const auto& clearcoat = source.clearcoat) {
            material.clearcoat = ClearcoatExtension{
                .clearcoatFactor = clearcoat->clearcoatFactor,
                .clearcoatTexture = toTextureRef(clearcoat->clearcoatTexture),
                .clearcoatRoughnessFactor = clearcoat->clearcoatRoughnessFactor,
                .clearcoatRoughnessTexture = toTextureRef(clearcoat->clearcoatRoughnessTexture),
                .clearcoatNormalTexture = toTextureRef(clearcoat->clearcoatNormalTexture),
                .clearcoatNormalScale = clearcoat->clearcoatNormalTexture
                                            ? clearcoat->clearcoatNormalTexture->scale
                                            : 1.0f,
            };
        }
        if (const auto& sheen = source.sheen) {
            material.sheen = SheenExtension{
                .sheenColorFactor = sheen->sheenColorFactor,
                .sheenColorTexture = toTextureRef(sheen->sheenColorTexture),
                .sheenRoughnessFactor = sheen->sheenRoughnessFactor,
                .sheenRoughnessTexture = toTextureRef(sheen->sheenRoughnessTexture),
            };
        }
        if (const auto& glossiness = source.specularGlossiness) {
            // The diffuse colour takes the base colour's place (SceneData.h); the metallic-
            // roughness fallback the file may also carry is for viewers without the extension.
            material.baseColorFactor = glossiness->diffuseFactor;
            material.baseColorTexture = toTextureRef(glossiness->diffuseTexture);
            material.specularGlossiness = SpecularGlossinessExtension{
                .specularFactor = glossiness->specularFactor,
                .glossinessFactor = glossiness->glossinessFactor,
                .specularGlossinessTexture = toTextureRef(glossiness->specularGlossinessTexture),
            };
        }
        if (const auto& iridescence = source.iridescence) {
            material.iridescence = IridescenceExtension{
                .iridescenceFactor = iridescence->iridescenceFactor,
                .iridescenceTexture = toTextureRef(iridescence->iridescenceTexture),
                .iridescenceIor = iridescence->iridescenceIor,
                .iridescenceThicknessMinimum = iridescence->iridescenceThicknessMinimum,
                .iridescenceThicknessMaximum = iridescence->iridescenceThicknessMaximum,
                .iridescenceThicknessTexture =
                    toTextureRef(iridescence->iridescenceThicknessTexture),
            };
        }
        if (const auto& anisotropy = source.anisotropy) {
            material.anisotropy = AnisotropyExtension{
                .anisotropyStrength = anisotropy->anisotropyStrength,
                .anisotropyRotation = anisotropy->anisotropyRotation,
                .anisotropyTexture = toTextureRef(anisotropy->anisotropyTexture),
            };
        }
        if (const auto& transmission = source.transmission) {
            material.transmission = TransmissionExtension{
                .transmissionFactor = transmission->transmissionFactor,
                .transmissionTexture = toTextureRef(transmission->transmissionTexture),
            };
        }
        if (const auto& volume = source.volume) {
            material.volume = VolumeExtension{
                .thicknessFactor = volume->thicknessFactor,
                .thicknessTexture = toTextureRef(volume->thicknessTexture),
                .attenuationDistance = volume->attenuationDistance,
                .attenuationColor = volume->attenuationColor,
            };
        }
        if (source.dispersion) {
            material.dispersion = DispersionExtension{.dispersion = *source.dispersion};
        }
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
    if (const auto& specular = material.specular) {
        add("KHR_materials_specular specularTexture", specular->specularTexture);
        add("KHR_materials_specular specularColorTexture", specular->specularColorTexture);
    }
    if (const auto& clearcoat = material.clearcoat) {
        add("KHR_materials_clearcoat clearcoatTexture", clearcoat->clearcoatTexture);
        add("KHR_materials_clearcoat clearcoatRoughnessTexture",
            clearcoat->clearcoatRoughnessTexture);
        add("KHR_materials_clearcoat clearcoatNormalTexture", clearcoat->clearcoatNormalTexture);
    }
    if (const auto& sheen = material.sheen) {
        add("KHR_materials_sheen sheenColorTexture", sheen->sheenColorTexture);
        add("KHR_materials_sheen sheenRoughnessTexture", sheen->sheenRoughnessTexture);
    }
    if (const auto& iridescence = material.iridescence) {
        add("KHR_materials_iridescence iridescenceTexture", iridescence->iridescenceTexture);
        add("KHR_materials_iridescence iridescenceThicknessTexture",
            iridescence->iridescenceThicknessTexture);
    }
    if (const auto& anisotropy = material.anisotropy) {
        add("KHR_materials_anisotropy anisotropyTexture", anisotropy->anisotropyTexture);
    }
    if (const auto& glossiness = material.specularGlossiness) {
        add("KHR_materials_pbrSpecularGlossiness diffuseTexture", glossiness->diffuseTexture);
        add("KHR_materials_pbrSpecularGlossiness specularGlossinessTexture",
            glossiness->specularGlossinessTexture);
    }
    if (const auto& transmission = material.transmission) {
        add("KHR_materials_transmission transmissionTexture", transmission->transmissionTexture);
    }
    if (const auto& volume = material.volume) {
        add("KHR_materials_volume thicknessTexture", volume->thicknessTexture);
    }
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
