#include "GltfBuilder.h"

#include <algorithm>
#include <fstream>
#include <limits>

namespace encore::test {
namespace {

std::uint32_t componentsOf(const std::string& type) {
    if (type == "VEC2") {
        return 2;
    }
    if (type == "VEC3") {
        return 3;
    }
    if (type == "VEC4") {
        return 4;
    }
    if (type == "MAT2") {
        return 4;
    }
    if (type == "MAT3") {
        return 9;
    }
    if (type == "MAT4") {
        return 16;
    }
    return 1;
}

std::string base64(std::span<const std::uint8_t> bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    text.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b0 = bytes[i];
        const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        text += kAlphabet[(triple >> 18) & 63];
        text += kAlphabet[(triple >> 12) & 63];
        text += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
        text += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
    }
    return text;
}

void writeBytes(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
}

template <typename Vec>
std::vector<float> flatten(const std::vector<Vec>& values) {
    std::vector<float> result;
    for (const Vec& value : values) {
        for (int c = 0; c < Vec::length(); ++c) {
            result.push_back(value[c]);
        }
    }
    return result;
}

}  // namespace

GltfBuilder::GltfBuilder() {
    mJson["asset"] = {{"version", "2.0"}, {"generator", "Encore GltfBuilder"}};
}

std::uint32_t GltfBuilder::append(const char* array, nlohmann::json value) {
    auto& list = mJson[array];
    if (!list.is_array()) {
        list = nlohmann::json::array();
    }
    list.push_back(std::move(value));
    return static_cast<std::uint32_t>(list.size() - 1);
}

std::uint32_t GltfBuilder::addBufferView(std::span<const std::uint8_t> bytes,
                                         std::optional<std::uint32_t> byteStride) {
    mBuffer.resize((mBuffer.size() + 3) / 4 * 4, 0);
    const std::size_t offset = mBuffer.size();
    mBuffer.insert(mBuffer.end(), bytes.begin(), bytes.end());
    if (!mJson.contains("buffers")) {
        mJson["buffers"] = nlohmann::json::array({nlohmann::json::object()});
    }
    mJson["buffers"][0]["byteLength"] = mBuffer.size();
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}};
    if (byteStride) {
        view["byteStride"] = *byteStride;
    }
    return append("bufferViews", std::move(view));
}

std::uint32_t GltfBuilder::addAccessor(std::uint32_t bufferView,
                                       std::uint32_t componentType,
                                       std::uint32_t count,
                                       const std::string& type,
                                       std::uint64_t byteOffset,
                                       bool normalized) {
    nlohmann::json accessor = {{"bufferView", bufferView},
                               {"componentType", componentType},
                               {"count", count},
                               {"type", type}};
    if (byteOffset) {
        accessor["byteOffset"] = byteOffset;
    }
    if (normalized) {
        accessor["normalized"] = true;
    }
    return append("accessors", std::move(accessor));
}

std::uint32_t GltfBuilder::addTypedAccessor(const std::vector<std::uint8_t>& bytes,
                                            const std::vector<double>& values,
                                            std::size_t componentSize,
                                            std::uint32_t componentType,
                                            const std::string& type,
                                            const AccessorOptions& options) {
    const std::uint32_t components = componentsOf(type);
    const std::size_t elementSize = componentSize * components;
    const std::size_t count = values.size() / components;
    std::vector<std::uint8_t> laidOut = bytes;
    if (options.byteStride && *options.byteStride > elementSize) {
        laidOut.assign(count * *options.byteStride, 0);
        for (std::size_t i = 0; i < count; ++i) {
            std::memcpy(laidOut.data() + i * *options.byteStride, bytes.data() + i * elementSize,
                        elementSize);
        }
    }
    const std::uint32_t view = addBufferView(laidOut, options.byteStride);
    const std::uint32_t accessor = addAccessor(
        view, componentType, static_cast<std::uint32_t>(count), type, 0, options.normalized);
    if (options.minMax && count > 0) {
        std::vector<double> min(components, std::numeric_limits<double>::infinity());
        std::vector<double> max(components, -std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < values.size(); ++i) {
            min[i % components] = std::min(min[i % components], values[i]);
            max[i % components] = std::max(max[i % components], values[i]);
        }
        mJson["accessors"][accessor]["min"] = min;
        mJson["accessors"][accessor]["max"] = max;
    }
    return accessor;
}

std::uint32_t GltfBuilder::addPositions(const std::vector<glm::vec3>& positions) {
    return addAccessor(flatten(positions), "VEC3", {.minMax = true});
}

std::uint32_t GltfBuilder::addNormals(const std::vector<glm::vec3>& normals) {
    return addAccessor(flatten(normals), "VEC3");
}

std::uint32_t GltfBuilder::addTexcoords(const std::vector<glm::vec2>& texcoords) {
    return addAccessor(flatten(texcoords), "VEC2");
}

std::uint32_t GltfBuilder::addColors(const std::vector<glm::vec4>& colors) {
    return addAccessor(flatten(colors), "VEC4");
}

GltfBuilder::PrimitiveDesc GltfBuilder::addFacingQuad(glm::vec2 min, glm::vec2 max, float z) {
    const glm::vec3 facing(0.0f, 0.0f, 1.0f);
    PrimitiveDesc quad;
    quad.attributes["POSITION"] =
        addPositions({{min.x, min.y, z}, {max.x, min.y, z}, {max.x, max.y, z}, {min.x, max.y, z}});
    quad.attributes["NORMAL"] = addNormals({facing, facing, facing, facing});
    quad.attributes["TEXCOORD_0"] = addTexcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    quad.indices = addIndices<std::uint16_t>({0, 1, 2, 0, 2, 3});
    return quad;
}

std::uint32_t GltfBuilder::addMesh(const std::vector<PrimitiveDesc>& primitives,
                                   const std::string& name) {
    nlohmann::json mesh;
    mesh["primitives"] = nlohmann::json::array();
    for (const PrimitiveDesc& desc : primitives) {
        nlohmann::json primitive;
        primitive["attributes"] = nlohmann::json::object();
        for (const auto& [semantic, accessor] : desc.attributes) {
            primitive["attributes"][semantic] = accessor;
        }
        if (desc.indices) {
            primitive["indices"] = *desc.indices;
        }
        if (desc.material) {
            primitive["material"] = *desc.material;
        }
        if (desc.mode) {
            primitive["mode"] = *desc.mode;
        }
        mesh["primitives"].push_back(std::move(primitive));
    }
    if (!name.empty()) {
        mesh["name"] = name;
    }
    return append("meshes", std::move(mesh));
}

std::uint32_t GltfBuilder::addNode(const NodeDesc& desc) {
    nlohmann::json node = nlohmann::json::object();
    if (!desc.name.empty()) {
        node["name"] = desc.name;
    }
    if (desc.mesh) {
        node["mesh"] = *desc.mesh;
    }
    if (!desc.children.empty()) {
        node["children"] = desc.children;
    }
    if (desc.matrix) {
        std::vector<float> values;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                values.push_back((*desc.matrix)[c][r]);
            }
        }
        node["matrix"] = values;
    } else {
        if (desc.translation) {
            node["translation"] = {desc.translation->x, desc.translation->y, desc.translation->z};
        }
        if (desc.rotation) {
            node["rotation"] = {desc.rotation->x, desc.rotation->y, desc.rotation->z,
                                desc.rotation->w};
        }
        if (desc.scale) {
            node["scale"] = {desc.scale->x, desc.scale->y, desc.scale->z};
        }
    }
    return append("nodes", std::move(node));
}

std::uint32_t GltfBuilder::addMaterial(const MaterialDesc& desc) {
    nlohmann::json pbr = {
        {"baseColorFactor",
         {desc.baseColor.r, desc.baseColor.g, desc.baseColor.b, desc.baseColor.a}},
        {"metallicFactor", desc.metallic},
        {"roughnessFactor", desc.roughness}};
    if (desc.baseColorTexture) {
        pbr["baseColorTexture"] = {{"index", *desc.baseColorTexture}};
    }
    nlohmann::json material = {{"pbrMetallicRoughness", pbr}, {"alphaMode", desc.alphaMode}};
    if (desc.alphaCutoff) {
        material["alphaCutoff"] = *desc.alphaCutoff;
    }
    if (desc.doubleSided) {
        material["doubleSided"] = true;
    }
    return append("materials", std::move(material));
}

std::uint32_t GltfBuilder::addTexture(const std::string& imageUri,
                                      std::optional<std::uint32_t> sampler) {
    const std::uint32_t image = append("images", {{"uri", imageUri}});
    nlohmann::json texture = {{"source", image}};
    if (sampler) {
        texture["sampler"] = *sampler;
    }
    return append("textures", std::move(texture));
}

std::uint32_t GltfBuilder::addSampler(std::optional<std::uint32_t> magFilter,
                                      std::optional<std::uint32_t> minFilter,
                                      std::uint32_t wrapS,
                                      std::uint32_t wrapT) {
    nlohmann::json sampler = {{"wrapS", wrapS}, {"wrapT", wrapT}};
    if (magFilter) {
        sampler["magFilter"] = *magFilter;
    }
    if (minFilter) {
        sampler["minFilter"] = *minFilter;
    }
    return append("samplers", std::move(sampler));
}

std::uint32_t GltfBuilder::addScene(const std::vector<std::uint32_t>& nodes) {
    const std::uint32_t scene = append("scenes", {{"nodes", nodes}});
    if (!mJson.contains("scene")) {
        mJson["scene"] = scene;
    }
    return scene;
}

nlohmann::json GltfBuilder::finalJson(std::optional<std::string> bufferUri) const {
    nlohmann::json result = mJson;
    if (bufferUri && result.contains("buffers") && result["buffers"].is_array() &&
        !result["buffers"].empty() && result["buffers"][0].is_object() &&
        !result["buffers"][0].contains("uri")) {
        result["buffers"][0]["uri"] = *bufferUri;
    }
    return result;
}

std::string GltfBuilder::toGltf() const {
    return finalJson("data:application/octet-stream;base64," + base64(mBuffer)).dump(1);
}

std::vector<std::uint8_t> GltfBuilder::toGltfBytes() const {
    const std::string text = toGltf();
    return {text.begin(), text.end()};
}

std::vector<std::uint8_t> GltfBuilder::toGlb() const {
    std::vector<std::uint8_t> bin = mBuffer;
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    return makeGlb(finalJson(std::nullopt).dump(),
                   mBuffer.empty() ? std::span<const std::uint8_t>() : std::span(bin));
}

std::filesystem::path GltfBuilder::writeGltf(const std::filesystem::path& dir,
                                             const std::string& name,
                                             BufferMode mode) const {
    const auto path = dir / (name + ".gltf");
    std::string text;
    if (mode == BufferMode::ExternalBin) {
        writeBytes(dir / (name + ".bin"), mBuffer);
        text = finalJson(name + ".bin").dump(1);
    } else {
        text = toGltf();
    }
    writeBytes(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
    return path;
}

std::filesystem::path GltfBuilder::writeGlb(const std::filesystem::path& dir,
                                            const std::string& name) const {
    const auto path = dir / (name + ".glb");
    writeBytes(path, toGlb());
    return path;
}

std::vector<std::uint8_t> makeGlb(const std::string& jsonText, std::span<const std::uint8_t> bin) {
    std::string json = jsonText;
    json.resize((json.size() + 3) / 4 * 4, ' ');
    std::vector<std::uint8_t> bytes;
    auto put32 = [&](std::uint32_t value) {
        for (int i = 0; i < 4; ++i) {
            bytes.push_back(std::uint8_t(value >> (8 * i)));
        }
    };
    const std::size_t binPadded = (bin.size() + 3) / 4 * 4;
    const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + binPadded);
    put32(0x46546C67);
    put32(2);
    put32(static_cast<std::uint32_t>(total));
    put32(static_cast<std::uint32_t>(json.size()));
    put32(0x4E4F534A);
    bytes.insert(bytes.end(), json.begin(), json.end());
    if (!bin.empty()) {
        put32(static_cast<std::uint32_t>(binPadded));
        put32(0x004E4942);
        bytes.insert(bytes.end(), bin.begin(), bin.end());
        bytes.resize(total, 0);
    }
    return bytes;
}

GltfBuilder fanWithoutTriangles() {
    GltfBuilder builder;
    const auto positions = builder.addPositions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    // NORMAL given: without it, flat normals are generated and the fan is drawn unindexed.
    const auto normals = builder.addNormals({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const auto indices = builder.addIndices(std::vector<std::uint16_t>{0, 1});
    const auto mesh = builder.addMesh({.attributes = {{"POSITION", positions}, {"NORMAL", normals}},
                                       .indices = indices,
                                       .mode = 6});
    builder.addScene({builder.addNode({.mesh = mesh})});
    return builder;
}

}  // namespace encore::test
