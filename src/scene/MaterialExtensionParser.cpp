// KHR_materials_* extensions: each one's reader (an invalid value is an error naming the
// material, the extension, the field and the value), its copy into scene::Material, and its
// textures for validation.

#include "scene/MaterialExtensionParser.h"

#include <algorithm>
#include <string>

namespace encore::scene {
namespace {

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

// A linear RGB colour whose components must lie in [0, 1]; an error names the field, the
// component and its value otherwise.
glm::vec3 readUnitColor(FieldReader& fields, std::string_view key, glm::vec3 fallback) {
    const glm::vec3 color = readVec3(fields, key, fallback);
    for (int channel = 0; channel < 3; ++channel) {
        const float value = color[channel];
        if (value < 0.0f || value > 1.0f) {
            fields.fail(ErrorCode::InvalidFormat,
                        fields.element() + " has an invalid " + std::string(key) + " (component " +
                            std::to_string(channel) + " is " + formatNumber(value) +
                            "; each must be between 0 and 1).");
            break;
        }
    }
    return color;
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
    volume.attenuationColor = readUnitColor(fields, "attenuationColor", glm::vec3(1.0f));
    return volume;
}

GltfDiffuseTransmission readDiffuseTransmission(FieldReader& fields) {
    GltfDiffuseTransmission result;
    result.diffuseTransmissionFactor =
        boundedNumber(fields, "diffuseTransmissionFactor", 0.0, 0.0, 1.0);
    result.diffuseTransmissionTexture = readTextureInfo(
        fields, fields.object("diffuseTransmissionTexture"), "diffuseTransmissionTexture", {});
    result.diffuseTransmissionColorFactor =
        readUnitColor(fields, "diffuseTransmissionColorFactor", glm::vec3(1.0f));
    result.diffuseTransmissionColorTexture =
        readTextureInfo(fields, fields.object("diffuseTransmissionColorTexture"),
                        "diffuseTransmissionColorTexture", {});
    return result;
}

}  // namespace

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
        } else if (name == "KHR_materials_diffuse_transmission") {
            material.diffuseTransmission = readDiffuseTransmission(fields);
        }
        if (fields.failed()) {
            reader.fail(fields.error().code, fields.error().message);
        }
    }
}

void convertMaterialExtensions(const GltfMaterial& source, Material& material) {
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
            .clearcoatNormalScale =
                clearcoat->clearcoatNormalTexture ? clearcoat->clearcoatNormalTexture->scale : 1.0f,
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
            .iridescenceThicknessTexture = toTextureRef(iridescence->iridescenceThicknessTexture),
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
    if (const auto& diffuse = source.diffuseTransmission) {
        material.diffuseTransmission = DiffuseTransmissionExtension{
            .diffuseTransmissionFactor = diffuse->diffuseTransmissionFactor,
            .diffuseTransmissionTexture = toTextureRef(diffuse->diffuseTransmissionTexture),
            .diffuseTransmissionColorFactor = diffuse->diffuseTransmissionColorFactor,
            .diffuseTransmissionColorTexture =
                toTextureRef(diffuse->diffuseTransmissionColorTexture),
        };
    }
}

void addExtensionTextureSlots(const GltfMaterial& material,
                              std::vector<GltfMaterialTextureSlot>& slots) {
    auto add = [&slots](std::string slot, const std::optional<GltfTextureInfo>& info) {
        if (info) {
            slots.push_back({std::move(slot), &*info});
        }
    };
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
    if (const auto& diffuse = material.diffuseTransmission) {
        add("KHR_materials_diffuse_transmission diffuseTransmissionTexture",
            diffuse->diffuseTransmissionTexture);
        add("KHR_materials_diffuse_transmission diffuseTransmissionColorTexture",
            diffuse->diffuseTransmissionColorTexture);
    }
}

}  // namespace encore::scene
