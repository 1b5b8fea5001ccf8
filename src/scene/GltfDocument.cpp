#include "scene/GltfDocument.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace encore::scene {
namespace {

// Extensions Encore reads and honours (material extensions: the loader fills them in and the
// renderer shades them). A file may require any of these.
constexpr std::array kSupportedExtensions = {
    std::string_view("KHR_mesh_quantization"),   std::string_view("KHR_draco_mesh_compression"),
    std::string_view("EXT_meshopt_compression"), std::string_view("EXT_mesh_gpu_instancing"),
    std::string_view("KHR_texture_transform"),   std::string_view("KHR_lights_punctual"),
    std::string_view("KHR_materials_variants"),  std::string_view("EXT_texture_webp"),
};

std::optional<ComponentType> componentTypeFromGl(std::uint64_t gl) {
    switch (gl) {
        case kGlByte:
            return ComponentType::Int8;
        case kGlUnsignedByte:
            return ComponentType::Uint8;
        case kGlShort:
            return ComponentType::Int16;
        case kGlUnsignedShort:
            return ComponentType::Uint16;
        case kGlUnsignedInt:
            return ComponentType::Uint32;
        case kGlFloat:
            return ComponentType::Float32;
        default:
            return std::nullopt;
    }
}

std::optional<std::pair<std::uint32_t, bool>> componentsOfType(const std::string& type) {
    if (type == "SCALAR") {
        return std::pair{1u, false};
    }
    if (type == "VEC2") {
        return std::pair{2u, false};
    }
    if (type == "VEC3") {
        return std::pair{3u, false};
    }
    if (type == "VEC4") {
        return std::pair{4u, false};
    }
    if (type == "MAT2") {
        return std::pair{4u, true};
    }
    if (type == "MAT3") {
        return std::pair{9u, true};
    }
    if (type == "MAT4") {
        return std::pair{16u, true};
    }
    return std::nullopt;
}

Result<std::vector<std::string>> readStringList(FieldReader& reader, std::string_view key) {
    std::vector<std::string> result;
    if (const Json* list = reader.array(key)) {
        for (const Json& item : *list) {
            if (!item.is_string()) {
                return makeError(ErrorCode::InvalidFormat,
                                 "The asset's '" + std::string(key) +
                                     "' holds a value that is not a string (" + describeJson(item) +
                                     ").");
            }
            result.push_back(item.get<std::string>());
        }
    }
    if (reader.failed()) {
        return reader.error();
    }
    return result;
}

// The object at root[key][name] ... along `path`, or nullptr where any step is missing or not an
// object (a lenient read of a document not checked yet).
const Json* findObject(const Json& root, std::initializer_list<std::string_view> path) {
    const Json* value = &root;
    for (std::string_view key : path) {
        if (!value->is_object()) {
            return nullptr;
        }
        const auto it = value->find(key);
        if (it == value->end()) {
            return nullptr;
        }
        value = &*it;
    }
    return value->is_object() ? value : nullptr;
}

// What a refusal of `extension` adds: for KHR_texture_basisu, why and which images need it.
std::string unsupportedExtensionNote(const Json& root, const std::string& extension) {
    if (extension != "KHR_texture_basisu") {
        return {};
    }
    std::set<std::uint64_t> indices;
    const auto textures = root.find("textures");
    if (root.is_object() && textures != root.end() && textures->is_array()) {
        for (const Json& texture : *textures) {
            const Json* basisu = findObject(texture, {"extensions", "KHR_texture_basisu"});
            const auto source = basisu ? basisu->find("source") : Json::const_iterator();
            if (basisu && source != basisu->end()) {
                if (const auto index = jsonToUint(*source)) {
                    indices.insert(*index);
                }
            }
        }
    }
    std::string images;
    const auto imageList = root.find("images");
    for (const std::uint64_t index : indices) {
        images += (images.empty() ? "" : ", ") + ("image " + std::to_string(index));
        if (imageList != root.end() && imageList->is_array() && index < imageList->size()) {
            const Json& image = (*imageList)[index];
            const auto uri = image.is_object() ? image.find("uri") : Json::const_iterator();
            if (image.is_object() && uri != image.end() && uri->is_string() &&
                !uri->get<std::string>().starts_with("data:")) {
                images += " ('" + uri->get<std::string>() + "')";
            }
        }
    }
    return " (Basis Universal textures need a transcoder, which no Debian package provides)" +
           (images.empty() ? std::string() : "; its KTX2 images need it: " + images);
}

Result<void> parseBuffers(const Json& root, GltfDocument& document) {
    return forEachElement(root, "buffers", "buffer", [&](FieldReader& reader, std::size_t) {
        GltfBuffer buffer;
        buffer.uri = reader.optionalString("uri");
        buffer.byteLength = reader.requiredUint("byteLength");
        if (const Json* extensions = reader.object("extensions")) {
            FieldReader ext(*extensions, reader.element() + " extensions");
            if (const Json* meshopt = ext.object("EXT_meshopt_compression")) {
                FieldReader fields(*meshopt, reader.element() + " EXT_meshopt_compression");
                buffer.meshoptFallback = fields.boolean("fallback", false);
                if (fields.failed()) {
                    reader.fail(fields.error().code, fields.error().message);
                }
            }
            if (ext.failed()) {
                reader.fail(ext.error().code, ext.error().message);
            }
        }
        document.buffers.push_back(std::move(buffer));
    });
}

Result<void> parseBufferViews(const Json& root, GltfDocument& document) {
    return forEachElement(root, "bufferViews", "bufferView", [&](FieldReader& reader, std::size_t) {
        GltfBufferView view;
        view.buffer = reader.requiredIndex("buffer");
        view.byteOffset = reader.uint("byteOffset", 0);
        view.byteLength = reader.requiredUint("byteLength");
        view.byteStride = reader.optionalUint("byteStride");
        if (const Json* meshopt = extensionObject(reader, "EXT_meshopt_compression")) {
            FieldReader fields(*meshopt, reader.element() + " EXT_meshopt_compression");
            GltfMeshoptCompression compression;
            compression.buffer = fields.requiredIndex("buffer");
            compression.byteOffset = fields.uint("byteOffset", 0);
            compression.byteLength = fields.requiredUint("byteLength");
            compression.byteStride = static_cast<std::uint32_t>(
                std::min<std::uint64_t>(fields.requiredUint("byteStride"), 0xFFFFFFFFu));
            compression.count = fields.requiredUint("count");
            compression.mode = fields.requiredString("mode");
            compression.filter = fields.string("filter", "NONE");
            view.meshopt = compression;
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        document.bufferViews.push_back(view);
    });
}

Result<void> parseAccessors(const Json& root, GltfDocument& document) {
    return forEachElement(root, "accessors", "accessor", [&](FieldReader& reader, std::size_t) {
        GltfAccessor accessor;
        accessor.bufferView = reader.optionalIndex("bufferView");
        accessor.byteOffset = reader.uint("byteOffset", 0);
        accessor.count = reader.requiredUint("count");
        const std::uint64_t gl = reader.requiredUint("componentType");
        accessor.type = reader.requiredString("type");
        accessor.normalized = reader.boolean("normalized", false);
        for (double value : reader.numbers("min")) {
            accessor.min.push_back(float(value));
        }
        for (double value : reader.numbers("max")) {
            accessor.max.push_back(float(value));
        }
        if (reader.failed()) {
            return;
        }
        const auto componentType = componentTypeFromGl(gl);
        if (!componentType) {
            reader.fail(
                ErrorCode::InvalidFormat,
                reader.element() + " has an unknown componentType (" + std::to_string(gl) + ").");
            return;
        }
        accessor.componentType = *componentType;
        accessor.glComponentType = static_cast<std::uint32_t>(gl);
        const auto components = componentsOfType(accessor.type);
        if (!components) {
            reader.fail(ErrorCode::InvalidFormat,
                        reader.element() + " has an unknown type ('" + accessor.type + "').");
            return;
        }
        accessor.componentCount = components->first;
        accessor.isMatrix = components->second;
        if (const Json* sparse = reader.object("sparse")) {
            FieldReader fields(*sparse, reader.element() + " sparse");
            GltfSparse result;
            result.count = fields.requiredUint("count");
            const Json* indices = fields.object("indices");
            const Json* values = fields.object("values");
            if (!fields.failed() && (!indices || !values)) {
                fields.fail(ErrorCode::InvalidFormat,
                            fields.element() + " lacks its 'indices' or 'values' object.");
            }
            if (indices && values) {
                FieldReader indexFields(*indices, fields.element() + " indices");
                result.indicesView = indexFields.requiredIndex("bufferView");
                result.indicesOffset = indexFields.uint("byteOffset", 0);
                result.indicesComponentType =
                    static_cast<std::uint32_t>(indexFields.requiredUint("componentType"));
                FieldReader valueFields(*values, fields.element() + " values");
                result.valuesView = valueFields.requiredIndex("bufferView");
                result.valuesOffset = valueFields.uint("byteOffset", 0);
                for (FieldReader* part : {&indexFields, &valueFields}) {
                    if (part->failed()) {
                        fields.fail(part->error().code, part->error().message);
                    }
                }
            }
            accessor.sparse = result;
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        document.accessors.push_back(std::move(accessor));
    });
}

AttributeMap readAttributeMap(FieldReader& reader, const Json& object, const std::string& what) {
    AttributeMap result;
    for (const auto& [name, value] : object.items()) {
        const auto index = jsonToUint(value);
        if (!index || *index >= 0xFFFFFFFFu) {
            reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an invalid " + what +
                                                      " '" + name + "' (expected an index, got " +
                                                      describeJson(value) + ").");
            return {};
        }
        result.emplace_back(name, static_cast<std::uint32_t>(*index));
    }
    return result;
}

Result<void> parseMeshes(const Json& root, GltfDocument& document) {
    return forEachElement(root, "meshes", "mesh", [&](FieldReader& reader, std::size_t index) {
        GltfMesh mesh;
        mesh.name = reader.string("name");
        if (reader.has("weights")) {
            const auto weights = reader.numbers("weights");
            mesh.weights = std::vector<float>(weights.begin(), weights.end());
        }
        const Json* primitives = reader.array("primitives");
        if (!primitives && !reader.failed()) {
            reader.fail(ErrorCode::InvalidFormat, reader.element() + " has no 'primitives'.");
        }
        for (std::size_t p = 0; primitives && p < primitives->size() && !reader.failed(); ++p) {
            FieldReader fields((*primitives)[p], "mesh " + std::to_string(index) + ", primitive " +
                                                     std::to_string(p));
            GltfPrimitive primitive;
            if (const Json* attributes = fields.object("attributes")) {
                primitive.attributes = readAttributeMap(fields, *attributes, "attribute");
            } else if (!fields.failed()) {
                fields.fail(ErrorCode::InvalidFormat, fields.element() + " has no 'attributes'.");
            }
            primitive.indices = fields.optionalIndex("indices");
            primitive.material = fields.optionalIndex("material");
            primitive.mode = static_cast<std::uint32_t>(
                std::min<std::uint64_t>(fields.uint("mode", 4), 0xFFFFFFFFu));
            if (const Json* targets = fields.array("targets")) {
                for (const Json& target : *targets) {
                    if (!target.is_object()) {
                        fields.fail(
                            ErrorCode::InvalidFormat,
                            fields.element() + " has a morph target that is not an object.");
                        break;
                    }
                    primitive.targets.push_back(readAttributeMap(fields, target, "morph target"));
                }
            }
            if (const Json* variants = extensionObject(fields, "KHR_materials_variants")) {
                primitive.variantMappings = readVariantMappings(fields, *variants);
            }
            if (const Json* draco = extensionObject(fields, "KHR_draco_mesh_compression")) {
                FieldReader dracoFields(*draco, fields.element() + " KHR_draco_mesh_compression");
                GltfDracoCompression compression;
                compression.bufferView = dracoFields.requiredIndex("bufferView");
                if (const Json* attributes = dracoFields.object("attributes")) {
                    compression.attributes =
                        readAttributeMap(dracoFields, *attributes, "Draco attribute");
                }
                primitive.draco = std::move(compression);
                if (dracoFields.failed()) {
                    fields.fail(dracoFields.error().code, dracoFields.error().message);
                }
            }
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
            mesh.primitives.push_back(std::move(primitive));
        }
        document.meshes.push_back(std::move(mesh));
    });
}

glm::mat4 localFromTrs(const std::vector<double>& t,
                       const std::vector<double>& r,
                       const std::vector<double>& s) {
    glm::mat4 result(1.0f);
    if (!t.empty()) {
        result = glm::translate(result, glm::vec3(t[0], t[1], t[2]));
    }
    if (!r.empty()) {
        // glTF stores quaternions as x, y, z, w; glm's constructor takes w first.
        const glm::quat rotation(static_cast<float>(r[3]), static_cast<float>(r[0]),
                                 static_cast<float>(r[1]), static_cast<float>(r[2]));
        const float length = glm::length(rotation);
        if (length > 0.0f) {
            result *= glm::mat4_cast(rotation / length);
        }
    }
    if (!s.empty()) {
        result = glm::scale(result, glm::vec3(s[0], s[1], s[2]));
    }
    return result;
}

// Translation, rotation and scale of an affine matrix without shear (what glTF allows for node
// matrices); a mirrored matrix gets a negative x scale.
void decomposeMatrix(const glm::mat4& matrix,
                     glm::vec3& translation,
                     glm::quat& rotation,
                     glm::vec3& scale) {
    translation = glm::vec3(matrix[3]);
    glm::mat3 linear(matrix);
    scale = glm::vec3(glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2]));
    if (glm::determinant(linear) < 0.0f) {
        scale.x = -scale.x;
    }
    for (int c = 0; c < 3; ++c) {
        if (scale[c] != 0.0f && std::isfinite(scale[c])) {
            linear[c] /= scale[c];
        }
    }
    rotation = glm::normalize(glm::quat_cast(linear));
    if (!std::isfinite(rotation.w + rotation.x + rotation.y + rotation.z)) {
        rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    }
}

Result<void> parseNodes(const Json& root, GltfDocument& document) {
    return forEachElement(root, "nodes", "node", [&](FieldReader& reader, std::size_t) {
        GltfNode node;
        node.name = reader.string("name");
        node.children = reader.indices("children");
        node.mesh = reader.optionalIndex("mesh");
        node.skin = reader.optionalIndex("skin");
        node.camera = reader.optionalIndex("camera");
        if (const Json* light = extensionObject(reader, "KHR_lights_punctual")) {
            FieldReader fields(*light, reader.element() + " KHR_lights_punctual");
            node.light = fields.requiredIndex("light");
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        const auto matrix = reader.numbers("matrix", 16);
        const auto translation = reader.numbers("translation", 3);
        const auto rotation = reader.numbers("rotation", 4);
        const auto scale = reader.numbers("scale", 3);
        if (reader.has("weights")) {
            const auto weights = reader.numbers("weights");
            node.weights = std::vector<float>(weights.begin(), weights.end());
        }
        if (matrix.size() == 16) {
            std::array<float, 16> values{};
            std::transform(matrix.begin(), matrix.end(), values.begin(),
                           [](double v) { return float(v); });
            node.local = glm::make_mat4(values.data());  // Column-major, like glTF.
            node.hasMatrix = true;
            decomposeMatrix(node.local, node.translation, node.rotation, node.scale);
        } else {
            node.local = localFromTrs(translation, rotation, scale);
            if (!translation.empty()) {
                node.translation = glm::vec3(translation[0], translation[1], translation[2]);
            }
            if (!rotation.empty()) {
                const glm::quat q{static_cast<float>(rotation[3]), static_cast<float>(rotation[0]),
                                  static_cast<float>(rotation[1]), static_cast<float>(rotation[2])};
                const float length = glm::length(q);
                if (length > 0.0f) {
                    node.rotation = q / length;
                }
            }
            if (!scale.empty()) {
                node.scale = glm::vec3(scale[0], scale[1], scale[2]);
            }
        }
        if (const Json* instancing = extensionObject(reader, "EXT_mesh_gpu_instancing")) {
            FieldReader fields(*instancing, reader.element() + " EXT_mesh_gpu_instancing");
            GltfInstancing result;
            if (const Json* attributes = fields.object("attributes")) {
                FieldReader attributeFields(*attributes, fields.element() + " attributes");
                result.translation = attributeFields.optionalIndex("TRANSLATION");
                result.rotation = attributeFields.optionalIndex("ROTATION");
                result.scale = attributeFields.optionalIndex("SCALE");
                if (attributeFields.failed()) {
                    fields.fail(attributeFields.error().code, attributeFields.error().message);
                }
            }
            node.instancing = result;
            if (fields.failed()) {
                reader.fail(fields.error().code, fields.error().message);
            }
        }
        document.nodes.push_back(std::move(node));
    });
}

Result<void> parseScenesAndSkins(const Json& root, GltfDocument& document) {
    ENCORE_TRY(forEachElement(root, "scenes", "scene", [&](FieldReader& reader, std::size_t) {
        document.scenes.push_back(reader.indices("nodes"));
    }));
    return forEachElement(root, "skins", "skin", [&](FieldReader& reader, std::size_t) {
        GltfSkin skin;
        skin.name = reader.string("name");
        skin.skeleton = reader.optionalIndex("skeleton");
        skin.inverseBindMatrices = reader.optionalIndex("inverseBindMatrices");
        skin.joints = reader.indices("joints");
        document.skins.push_back(std::move(skin));
    });
}

}  // namespace

bool isSupportedExtension(std::string_view name) {
    return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), name) !=
               kSupportedExtensions.end() ||
           std::find(kShadedMaterialExtensions.begin(), kShadedMaterialExtensions.end(), name) !=
               kShadedMaterialExtensions.end();
}

Result<GltfDocument> parseDocument(const Json& root) {
    if (!root.is_object()) {
        return makeError(ErrorCode::InvalidFormat,
                         "The glTF JSON is not an object (got " + describeJson(root) + ").");
    }
    FieldReader top(root, "The glTF document");
    const Json* asset = top.object("asset");
    if (top.failed()) {
        return top.error();
    }
    if (!asset) {
        return makeError(ErrorCode::InvalidFormat,
                         "The glTF JSON has no 'asset' object (is it a glTF file?).");
    }
    GltfDocument document;
    FieldReader assetFields(*asset, "The asset");
    document.version = assetFields.requiredString("version");
    if (assetFields.failed()) {
        return assetFields.error();
    }
    if (document.version.size() < 2 || document.version.compare(0, 2, "2.") != 0) {
        return makeError(ErrorCode::Unsupported, "The asset's glTF version (" + document.version +
                                                     ") is not supported; Encore reads glTF 2.x.");
    }
    ENCORE_TRY_ASSIGN(document.extensionsUsed, readStringList(top, "extensionsUsed"));
    ENCORE_TRY_ASSIGN(document.extensionsRequired, readStringList(top, "extensionsRequired"));
    for (const std::string& extension : document.extensionsRequired) {
        if (!isSupportedExtension(extension)) {
            return makeError(ErrorCode::Unsupported,
                             "The asset requires the extension " + extension +
                                 ", which Encore does not support" +
                                 unsupportedExtensionNote(root, extension) + ".");
        }
    }
    document.scene = top.optionalIndex("scene");
    if (top.failed()) {
        return top.error();
    }
    ENCORE_TRY(parseBuffers(root, document));
    ENCORE_TRY(parseBufferViews(root, document));
    ENCORE_TRY(parseAccessors(root, document));
    ENCORE_TRY(parseMeshes(root, document));
    ENCORE_TRY(parseNodes(root, document));
    ENCORE_TRY(parseScenesAndSkins(root, document));
    ENCORE_TRY(parseAnimations(root, document));
    ENCORE_TRY(parseLightsAndCameras(root, document));
    ENCORE_TRY(parseMaterialElements(root, document));
    ENCORE_TRY_ASSIGN(document.variants, parseVariantNames(root));
    return document;
}

}  // namespace encore::scene
