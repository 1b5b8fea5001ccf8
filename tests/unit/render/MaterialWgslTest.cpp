#include <gtest/gtest.h>

#include <cctype>
#include <cstddef>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "render/MaterialSlots.h"
#include "render/MaterialUniform.h"
#include "shaders/EmbeddedFiles.h"

// material.wgsl is written by hand; these tests hold it to the C++ side (the slot table,
// MaterialUniform, the kMaterial* bits and ShadingModel), reading the text embedded in the
// binary, so neither side can change alone.

namespace encore::render {
namespace {

std::string embeddedWgsl(std::string_view name) {
    for (const shaders::EmbeddedFile& file : shaders::wgslFiles()) {
        if (file.name == name) {
            return std::string(file.contents);
        }
    }
    ADD_FAILURE() << name << " is not embedded";
    return {};
}

// material.wgsl without its comments.
std::string materialWgsl() {
    static const std::string source =
        std::regex_replace(embeddedWgsl("material.wgsl"), std::regex("//[^\n]*"), "");
    return source;
}

// The body of `struct name { ... }`.
std::string structBody(const std::string& source, const std::string& name) {
    std::smatch match;
    if (!std::regex_search(source, match, std::regex("struct\\s+" + name + "\\s*\\{([^}]*)\\}"))) {
        ADD_FAILURE() << "material.wgsl declares no struct " << name;
        return {};
    }
    return match[1];
}

struct WgslField {
    std::string name;
    std::string type;
};

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    const auto last = text.find_last_not_of(" \t\r\n");
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

// The `name: type` fields of a struct body, split at the commas outside template brackets.
std::vector<WgslField> structFields(const std::string& body) {
    std::vector<WgslField> fields;
    std::string current;
    int depth = 0;
    auto finish = [&fields, &current] {
        const std::string field = trimmed(current);
        current.clear();
        if (field.empty()) {
            return;
        }
        const auto colon = field.find(':');
        if (colon == std::string::npos) {
            ADD_FAILURE() << "unreadable field '" << field << "'";
            return;
        }
        fields.push_back({trimmed(field.substr(0, colon)), trimmed(field.substr(colon + 1))});
    };
    for (const char c : body) {
        depth += c == '<' ? 1 : c == '>' ? -1 : 0;
        if (c == ',' && depth == 0) {
            finish();
        } else {
            current += c;
        }
    }
    finish();
    return fields;
}

// `const NAME = Nu;` for every NAME starting with `prefix`.
std::map<std::string, std::uint32_t> unsignedConstants(const std::string& prefix) {
    const std::string source = materialWgsl();
    std::map<std::string, std::uint32_t> constants;
    const std::regex constant("const\\s+(" + prefix + "\\w*)\\s*=\\s*(\\d+)u\\s*;");
    for (std::sregex_iterator it(source.begin(), source.end(), constant), end; it != end; ++it) {
        EXPECT_TRUE(constants.emplace((*it)[1], std::stoul((*it)[2])).second)
            << (*it)[1] << " is declared twice";
    }
    return constants;
}

struct WgslBinding {
    std::uint32_t binding = 0;
    std::string type;
};

// Every `@group(2) @binding(N) var NAME: TYPE` of material.wgsl and of material_uniform.wgsl
// (the uniform, which the visibility shading replaces), by name.
std::map<std::string, WgslBinding> groupTwoBindings() {
    const std::string source =
        materialWgsl() +
        std::regex_replace(embeddedWgsl("material_uniform.wgsl"), std::regex("//[^\n]*"), "");
    std::map<std::string, WgslBinding> bindings;
    const std::regex declaration(
        R"(@group\((\d+)\)\s*@binding\((\d+)\)\s*var(?:<\w+>)?\s+(\w+)\s*:\s*([\w<>]+))");
    for (std::sregex_iterator it(source.begin(), source.end(), declaration), end; it != end; ++it) {
        EXPECT_EQ((*it)[1], "2") << (*it)[3] << " is outside the material group";
        const bool added =
            bindings.emplace((*it)[3], WgslBinding{std::uint32_t(std::stoul((*it)[2])), (*it)[4]})
                .second;
        EXPECT_TRUE(added) << (*it)[3] << " is bound twice";
    }
    return bindings;
}

// Each slot of the table has its texture, and each entry of the sampler palette its sampler,
// at the bindings MaterialResources and BindGroupLayouts use, and group 2 holds nothing else
// but the uniform.
TEST(MaterialWgslTest, EverySlotOfTheTableIsBoundUnderItsNames) {
    const auto bindings = groupTwoBindings();
    ASSERT_TRUE(bindings.contains("material"));
    EXPECT_EQ(bindings.at("material").binding, 0u);
    EXPECT_EQ(bindings.at("material").type, "Material");
    for (std::uint32_t entry = 0; entry < kMaterialSamplerCount; ++entry) {
        const std::string sampler = "materialSampler" + std::to_string(entry);
        ASSERT_TRUE(bindings.contains(sampler)) << "material.wgsl does not bind " << sampler;
        EXPECT_EQ(bindings.at(sampler).binding, materialSamplerBinding(entry)) << sampler;
        EXPECT_EQ(bindings.at(sampler).type, "sampler") << sampler;
    }
    for (const TextureSlotInfo& slot : textureSlots()) {
        const std::uint32_t index = std::uint32_t(slot.slot);
        const std::string texture(slot.textureName);
        ASSERT_TRUE(bindings.contains(texture)) << "material.wgsl does not bind " << texture;
        EXPECT_EQ(bindings.at(texture).binding, materialTextureBinding(index)) << texture;
        EXPECT_EQ(bindings.at(texture).type, "texture_2d<f32>") << texture;
    }
    EXPECT_EQ(bindings.size(), 1 + kMaterialSamplerCount + kMaterialTextureSlotCount);
    std::vector<bool> used(bindings.size(), false);
    for (const auto& [name, binding] : bindings) {
        ASSERT_LT(binding.binding, used.size()) << name << " leaves a gap in the bindings";
        EXPECT_FALSE(used[binding.binding]) << name << " reuses binding " << binding.binding;
        used[binding.binding] = true;
    }
}

// slotSample and slotSampleGrad switch over every palette entry: entry i samples through
// materialSampler<i>, and an entry past the palette falls to materialSampler0.
TEST(MaterialWgslTest, SlotSamplingSwitchesOverEveryPaletteEntry) {
    const std::string source = materialWgsl();
    for (const std::string function : {"slotSample", "slotSampleGrad"}) {
        std::smatch match;
        ASSERT_TRUE(std::regex_search(
            source, match, std::regex("fn\\s+" + function + "\\s*\\(([\\s\\S]*?)\\n\\}")))
            << "material.wgsl declares no " << function;
        const std::string body = match[1];
        for (std::uint32_t entry = 1; entry < kMaterialSamplerCount; ++entry) {
            const std::regex sampleCase("case\\s+" + std::to_string(entry) +
                                        "u\\s*:\\s*\\{[^}]*materialSampler" +
                                        std::to_string(entry) + "\\b");
            EXPECT_TRUE(std::regex_search(body, sampleCase)) << function << ", entry " << entry;
        }
        EXPECT_TRUE(
            std::regex_search(body, std::regex("default\\s*:\\s*\\{[^}]*materialSampler0\\b")))
            << function;
    }
}

// mesh.wgsl indexes material.slots with kXSlot; X is the slot's texture name without "Texture".
TEST(MaterialWgslTest, SlotIndicesMatchTheTable) {
    const auto constants = unsignedConstants("k");
    std::size_t slotConstants = 0;
    for (const auto& [name, value] : constants) {
        slotConstants += name.ends_with("Slot") ? 1 : 0;
    }
    EXPECT_EQ(slotConstants, kMaterialTextureSlotCount);
    for (const TextureSlotInfo& slot : textureSlots()) {
        std::string name(slot.textureName.substr(0, slot.textureName.size() - 7));
        name[0] = char(std::toupper(static_cast<unsigned char>(name[0])));
        name = "k" + name + "Slot";
        ASSERT_TRUE(constants.contains(name)) << "material.wgsl does not declare " << name;
        EXPECT_EQ(constants.at(name), std::uint32_t(slot.slot)) << name;
    }
}

TEST(MaterialWgslTest, FeatureBitsAndShadingModelsMatchTheCpp) {
    const std::map<std::string, std::uint32_t> features = {
        {"kMaterialNormalMap", kMaterialNormalMap},
        {"kMaterialClearcoatNormalMap", kMaterialClearcoatNormalMap},
        {"kMaterialClearcoat", kMaterialClearcoat},
        {"kMaterialSheen", kMaterialSheen},
        {"kMaterialSpecular", kMaterialSpecular},
        {"kMaterialIridescence", kMaterialIridescence},
        {"kMaterialAnisotropy", kMaterialAnisotropy},
        {"kMaterialAnisotropyTexture", kMaterialAnisotropyTexture},
        {"kMaterialTransmission", kMaterialTransmission},
        {"kMaterialVolume", kMaterialVolume},
        {"kMaterialDiffuseTransmission", kMaterialDiffuseTransmission},
    };
    EXPECT_EQ(unsignedConstants("kMaterial"), features);
    std::uint32_t all = 0;
    for (const auto& [name, bit] : features) {
        EXPECT_EQ(bit & (bit - 1), 0u) << name << " is not a single bit";
        EXPECT_EQ(all & bit, 0u) << name << " reuses a bit";
        all |= bit;
    }

    const std::map<std::string, std::uint32_t> models = {
        {"kModelMetallicRoughness", std::uint32_t(ShadingModel::MetallicRoughness)},
        {"kModelSpecularGlossiness", std::uint32_t(ShadingModel::SpecularGlossiness)},
        {"kModelUnlit", std::uint32_t(ShadingModel::Unlit)},
    };
    EXPECT_EQ(unsignedConstants("kModel"), models);
}

// The WGSL `Material` is MaterialUniform: the same fields at the same offsets (vec4s, then the
// slots array), the same size.
TEST(MaterialWgslTest, MaterialStructMatchesMaterialUniform) {
    const std::string source = materialWgsl();
    const std::vector<WgslField> slotFields = structFields(structBody(source, "TextureSlot"));
    ASSERT_EQ(slotFields.size(), 2u);
    for (const WgslField& field : slotFields) {
        EXPECT_EQ(field.type, "vec4f") << "TextureSlot." << field.name;
    }
    EXPECT_EQ(sizeof(TextureSlotUniform), slotFields.size() * 16);

    struct CppField {
        std::size_t offset;
        const char* type;
    };
    const std::map<std::string, CppField> cpp = {
        {"baseColorFactor", {offsetof(MaterialUniform, baseColorFactor), "vec4f"}},
        {"emissive", {offsetof(MaterialUniform, emissive), "vec4f"}},
        {"metallicRoughness", {offsetof(MaterialUniform, metallicRoughness), "vec4f"}},
        {"alpha", {offsetof(MaterialUniform, alpha), "vec4f"}},
        {"specular", {offsetof(MaterialUniform, specular), "vec4f"}},
        {"clearcoat", {offsetof(MaterialUniform, clearcoat), "vec4f"}},
        {"sheen", {offsetof(MaterialUniform, sheen), "vec4f"}},
        {"specularGlossiness", {offsetof(MaterialUniform, specularGlossiness), "vec4f"}},
        {"iridescence", {offsetof(MaterialUniform, iridescence), "vec4f"}},
        {"anisotropy", {offsetof(MaterialUniform, anisotropy), "vec4f"}},
        {"transmission", {offsetof(MaterialUniform, transmission), "vec4f"}},
        {"attenuationColor", {offsetof(MaterialUniform, attenuationColor), "vec4f"}},
        {"diffuseTransmission", {offsetof(MaterialUniform, diffuseTransmission), "vec4f"}},
        {"flags", {offsetof(MaterialUniform, flags), "vec4u"}},
    };
    const std::vector<WgslField> fields = structFields(structBody(source, "Material"));
    ASSERT_FALSE(fields.empty());
    // Every field but the last is a 16-byte vector at 16 * its index.
    std::size_t offset = 0;
    for (std::size_t i = 0; i + 1 < fields.size(); ++i, offset += 16) {
        const WgslField& field = fields[i];
        ASSERT_TRUE(cpp.contains(field.name)) << "MaterialUniform has no field " << field.name;
        EXPECT_EQ(cpp.at(field.name).offset, offset) << field.name;
        EXPECT_EQ(field.type, cpp.at(field.name).type) << field.name;
    }
    EXPECT_EQ(fields.size() - 1, cpp.size());
    // Then the slots, one per slot of the table.
    const WgslField& slots = fields.back();
    EXPECT_EQ(slots.name, "slots");
    EXPECT_EQ(offsetof(MaterialUniform, slots), offset);
    std::smatch array;
    const std::regex arrayType(R"(array<\s*TextureSlot\s*,\s*(\d+)\s*>)");
    ASSERT_TRUE(std::regex_match(slots.type, array, arrayType)) << slots.type;
    const std::size_t slotCount = std::stoul(array[1]);
    EXPECT_EQ(slotCount, kMaterialTextureSlotCount);
    EXPECT_EQ(sizeof(MaterialUniform), offset + slotCount * slotFields.size() * 16);
}

}  // namespace
}  // namespace encore::render
