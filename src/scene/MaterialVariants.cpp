// KHR_materials_variants: the root's variant names, each primitive's mappings, and finding a
// variant by name or index. The names are read the same way by the loader and by
// readVariantNames, which looks at a file's JSON alone.

#include "encore/scene/SceneData.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

constexpr std::string_view kExtension = "KHR_materials_variants";

// Reads `size` bytes at `offset` of an open file; false when the file is shorter.
bool readAt(std::ifstream& file, std::uint64_t offset, std::size_t size, std::uint8_t* out) {
    file.seekg(static_cast<std::streamoff>(offset));
    file.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(size));
    return file.good();
}

// The JSON of a .gltf, or a .glb's JSON chunk, without reading the rest of a .glb.
Result<std::vector<std::uint8_t>> readJsonText(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        return makeError(ErrorCode::FileNotFound, "Cannot open '" + path.string() + "'.");
    }
    std::uint8_t header[20] = {};
    file.read(reinterpret_cast<char*>(header), sizeof(header));
    const std::size_t got = static_cast<std::size_t>(file.gcount());
    file.clear();
    if (got < 4 || !hasGlbMagic(std::span(header, got))) {
        file.seekg(0);
        std::vector<std::uint8_t> text((std::istreambuf_iterator<char>(file)),
                                       std::istreambuf_iterator<char>());
        return text;
    }
    // GLB: a 12-byte header, then the JSON chunk's length and type.
    std::uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, header + 12, sizeof(jsonLength));
    std::error_code ec;
    const std::uintmax_t fileSize = std::filesystem::file_size(path, ec);
    std::vector<std::uint8_t> text;
    if (got == sizeof(header) && !ec && jsonLength <= fileSize - sizeof(header)) {
        text.resize(jsonLength);
    }
    if (text.size() != jsonLength || !readAt(file, sizeof(header), jsonLength, text.data())) {
        return makeError(ErrorCode::InvalidFormat, "'" + path.string() +
                                                       "' is a GLB file whose JSON chunk is "
                                                       "cut short.");
    }
    return text;
}

}  // namespace

Result<std::vector<std::string>> parseVariantNames(const Json& root) {
    FieldReader top(root, "The glTF document");
    const Json* extension = extensionObject(top, kExtension);
    if (top.failed()) {
        return top.error();
    }
    if (!extension) {
        return std::vector<std::string>{};
    }
    FieldReader fields(*extension, "The asset's " + std::string(kExtension));
    const Json* list = fields.array("variants");
    if (!list && !fields.failed()) {
        fields.fail(ErrorCode::InvalidFormat, fields.element() + " has no 'variants' array.");
    }
    std::vector<std::string> names;
    for (std::size_t i = 0; list && i < list->size() && !fields.failed(); ++i) {
        FieldReader variant((*list)[i], fields.element() + " variant " + std::to_string(i));
        names.push_back(variant.requiredString("name"));
        if (variant.failed()) {
            fields.fail(variant.error().code, variant.error().message);
        }
    }
    if (fields.failed()) {
        return fields.error();
    }
    return names;
}

std::vector<GltfVariantMapping> readVariantMappings(FieldReader& primitive, const Json& extension) {
    FieldReader fields(extension, primitive.element() + " " + std::string(kExtension));
    std::vector<GltfVariantMapping> mappings;
    const Json* list = fields.array("mappings");
    if (!list && !fields.failed()) {
        fields.fail(ErrorCode::InvalidFormat, fields.element() + " has no 'mappings' array.");
    }
    for (std::size_t i = 0; list && i < list->size() && !fields.failed(); ++i) {
        FieldReader mapping((*list)[i], fields.element() + " mapping " + std::to_string(i));
        GltfVariantMapping result;
        result.material = mapping.requiredIndex("material");
        result.variants = mapping.indices("variants");
        if (!mapping.failed() && result.variants.empty()) {
            mapping.fail(ErrorCode::InvalidFormat,
                         mapping.element() +
                             " names no variant (its 'variants' is missing or "
                             "empty).");
        }
        if (mapping.failed()) {
            fields.fail(mapping.error().code, mapping.error().message);
        }
        mappings.push_back(std::move(result));
    }
    if (fields.failed()) {
        primitive.fail(fields.error().code, fields.error().message);
    }
    return mappings;
}

Result<std::vector<VariantMapping>> convertVariantMappings(const GltfPrimitive& primitive,
                                                           const std::string& name) {
    std::vector<VariantMapping> result;
    for (const GltfVariantMapping& mapping : primitive.variantMappings) {
        for (const std::uint32_t variant : mapping.variants) {
            result.push_back({VariantId(variant), MaterialId(mapping.material)});
        }
    }
    std::stable_sort(
        result.begin(), result.end(),
        [](const VariantMapping& a, const VariantMapping& b) { return a.variant < b.variant; });
    for (std::size_t i = 1; i < result.size(); ++i) {
        if (result[i].variant == result[i - 1].variant) {
            // The extension allows one material per variant and primitive.
            return makeError(ErrorCode::InvalidFormat,
                             name + " " + std::string(kExtension) + " maps variant " +
                                 std::to_string(result[i].variant.value) +
                                 " more than once (to materials " +
                                 std::to_string(result[i - 1].material.value) + " and " +
                                 std::to_string(result[i].material.value) + ").");
        }
    }
    return result;
}

std::optional<VariantId> findVariant(std::span<const std::string> variants,
                                     std::string_view nameOrIndex) {
    for (std::size_t v = 0; v < variants.size(); ++v) {
        if (variants[v] == nameOrIndex) {
            return VariantId(v);
        }
    }
    std::size_t index = 0;
    const char* end = nameOrIndex.data() + nameOrIndex.size();
    const auto [next, error] = std::from_chars(nameOrIndex.data(), end, index);
    if (error == std::errc() && next == end && !nameOrIndex.empty() && index < variants.size()) {
        return VariantId(index);
    }
    return std::nullopt;
}

std::optional<VariantId> findVariant(const SceneData& scene, std::string_view nameOrIndex) {
    return findVariant(scene.variants, nameOrIndex);
}

std::string describeVariants(std::span<const std::string> variants) {
    if (variants.empty()) {
        return "none";
    }
    std::string text;
    for (std::size_t v = 0; v < variants.size(); ++v) {
        text += (v == 0 ? "" : ", ") + std::to_string(v) + " '" + variants[v] + "'";
    }
    return text;
}

Result<VariantId> resolveVariant(std::span<const std::string> variants,
                                 std::string_view nameOrIndex,
                                 const std::string& file) {
    if (const auto found = findVariant(variants, nameOrIndex)) {
        return *found;
    }
    return makeError(ErrorCode::InvalidArgument,
                     "'" + file + "' has no material variant '" + std::string(nameOrIndex) + "' (" +
                         (variants.empty() ? std::string("it uses no KHR_materials_variants")
                                           : "its variants: " + describeVariants(variants)) +
                         "; give a name or an index).");
}

Result<VariantId> resolveVariant(const SceneData& scene, std::string_view nameOrIndex) {
    return resolveVariant(scene.variants, nameOrIndex, scene.sourcePath.string());
}

Result<std::vector<std::string>> readVariantNames(const std::filesystem::path& path) {
    ENCORE_TRY_ASSIGN(auto text, readJsonText(path));
    // What the loader forgives too: a UTF-8 byte order mark, NULs padding a GLB's JSON.
    std::span<const std::uint8_t> json = text;
    if (json.size() >= 3 && json[0] == 0xEF && json[1] == 0xBB && json[2] == 0xBF) {
        json = json.subspan(3);
    }
    while (!json.empty() && json.back() == 0) {
        json = json.first(json.size() - 1);
    }
    // No exceptions: a file that does not parse is the loader's to describe.
    const Json root = Json::parse(json.begin(), json.end(), nullptr, false);
    if (root.is_discarded()) {
        return makeError(ErrorCode::InvalidFormat,
                         "'" + path.string() + "' does not hold valid glTF JSON.");
    }
    auto names = parseVariantNames(root);
    if (!names) {
        return names.error().withContext(path.string());
    }
    return names;
}

}  // namespace encore::scene
