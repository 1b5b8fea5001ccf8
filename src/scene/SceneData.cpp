#include "encore/scene/SceneData.h"

#include <algorithm>
#include <cstring>

namespace encore::scene {
namespace {

template <typename T>
T readAs(const std::uint8_t* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

float readComponent(const std::uint8_t* bytes, ComponentType type, bool normalized) {
    switch (type) {
        case ComponentType::Int8: {
            const auto value = readAs<std::int8_t>(bytes);
            return normalized ? std::max(value / 127.0f, -1.0f) : float(value);
        }
        case ComponentType::Uint8: {
            const auto value = readAs<std::uint8_t>(bytes);
            return normalized ? value / 255.0f : float(value);
        }
        case ComponentType::Int16: {
            const auto value = readAs<std::int16_t>(bytes);
            return normalized ? std::max(value / 32767.0f, -1.0f) : float(value);
        }
        case ComponentType::Uint16: {
            const auto value = readAs<std::uint16_t>(bytes);
            return normalized ? value / 65535.0f : float(value);
        }
        case ComponentType::Uint32: {
            const auto value = readAs<std::uint32_t>(bytes);
            return normalized ? float(double(value) / 4294967295.0) : float(value);
        }
        case ComponentType::Float32:
            return readAs<float>(bytes);
    }
    return 0.0f;
}

}  // namespace

std::uint32_t componentSize(ComponentType type) {
    switch (type) {
        case ComponentType::Int8:
        case ComponentType::Uint8:
            return 1;
        case ComponentType::Int16:
        case ComponentType::Uint16:
            return 2;
        case ComponentType::Uint32:
        case ComponentType::Float32:
            return 4;
    }
    return 4;
}

std::string_view semanticName(Semantic semantic) {
    switch (semantic) {
        case Semantic::Position:
            return "POSITION";
        case Semantic::Normal:
            return "NORMAL";
        case Semantic::Tangent:
            return "TANGENT";
        case Semantic::Texcoord0:
            return "TEXCOORD_0";
        case Semantic::Texcoord1:
            return "TEXCOORD_1";
        case Semantic::Color0:
            return "COLOR_0";
        case Semantic::Joints0:
            return "JOINTS_0";
        case Semantic::Weights0:
            return "WEIGHTS_0";
        case Semantic::Joints1:
            return "JOINTS_1";
        case Semantic::Weights1:
            return "WEIGHTS_1";
    }
    return "UNKNOWN";
}

std::optional<AccessorId> Primitive::attribute(Semantic semantic) const {
    for (const VertexAttribute& entry : attributes) {
        if (entry.semantic == semantic) {
            return entry.accessor;
        }
    }
    return std::nullopt;
}

MaterialId Primitive::materialFor(std::optional<VariantId> variant) const {
    if (variant) {
        for (const VariantMapping& mapping : variantMaterials) {
            if (mapping.variant == *variant) {
                return mapping.material;
            }
        }
    }
    return material;
}

std::span<const std::uint8_t> SceneData::accessorBytes(AccessorId id) const {
    // The loader validated every range; the checks here keep a hand-built SceneData from
    // turning into an out-of-bounds read.
    if (id.index() >= accessors.size()) {
        return {};
    }
    const Accessor& accessor = accessors[id.index()];
    if (accessor.count == 0 || accessor.view.index() >= bufferViews.size()) {
        return {};
    }
    const BufferView& view = bufferViews[accessor.view.index()];
    if (view.buffer.index() >= buffers.size()) {
        return {};
    }
    const auto& bytes = buffers[view.buffer.index()].bytes;
    const std::uint64_t stride = accessor.byteStride ? accessor.byteStride : accessor.elementSize();
    const std::uint64_t length = (accessor.count - 1ull) * stride + accessor.elementSize();
    const std::uint64_t start = view.byteOffset + accessor.byteOffset;
    if (accessor.byteOffset > view.byteLength || length > view.byteLength - accessor.byteOffset ||
        view.byteOffset > bytes.size() || accessor.byteOffset > bytes.size() - view.byteOffset ||
        length > bytes.size() - start) {
        return {};
    }
    return std::span<const std::uint8_t>(bytes).subspan(start, length);
}

std::vector<std::uint8_t> SceneData::packedAccessorBytes(AccessorId id) const {
    const auto bytes = accessorBytes(id);
    if (bytes.empty()) {
        return {};
    }
    const Accessor& accessor = accessors[id.index()];
    const std::size_t elementSize = accessor.elementSize();
    const std::size_t stride = accessor.byteStride ? accessor.byteStride : elementSize;
    std::vector<std::uint8_t> packed(elementSize * accessor.count);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        std::memcpy(packed.data() + i * elementSize, bytes.data() + i * stride, elementSize);
    }
    return packed;
}

std::vector<std::uint32_t> SceneData::readIndices(AccessorId id) const {
    const auto bytes = accessorBytes(id);
    if (bytes.empty()) {
        return {};
    }
    const Accessor& accessor = accessors[id.index()];
    const std::size_t stride = accessor.byteStride ? accessor.byteStride : accessor.elementSize();
    std::vector<std::uint32_t> indices(accessor.count);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const std::uint8_t* element = bytes.data() + i * stride;
        switch (accessor.componentType) {
            case ComponentType::Uint8:
            case ComponentType::Int8:
                indices[i] = element[0];
                break;
            case ComponentType::Uint16:
            case ComponentType::Int16:
                indices[i] = readAs<std::uint16_t>(element);
                break;
            case ComponentType::Uint32:
            case ComponentType::Float32:
                indices[i] = readAs<std::uint32_t>(element);
                break;
        }
    }
    return indices;
}

std::vector<glm::vec4> SceneData::readFloats(AccessorId id) const {
    const auto bytes = accessorBytes(id);
    if (bytes.empty()) {
        return {};
    }
    const Accessor& accessor = accessors[id.index()];
    const std::size_t stride = accessor.byteStride ? accessor.byteStride : accessor.elementSize();
    const std::size_t size = componentSize(accessor.componentType);
    const int components = std::min<int>(accessor.componentCount, 4);
    std::vector<glm::vec4> values(accessor.count, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const std::uint8_t* element = bytes.data() + i * stride;
        for (int c = 0; c < components; ++c) {
            values[i][c] =
                readComponent(element + c * size, accessor.componentType, accessor.normalized);
        }
    }
    return values;
}

std::size_t SceneData::primitiveCount() const {
    std::size_t count = 0;
    for (const Mesh& mesh : meshes) {
        count += mesh.primitives.size();
    }
    return count;
}

std::uint64_t SceneData::drawnTriangleCount() const {
    std::uint64_t triangles = 0;
    for (const Instance& instance : instances) {
        for (const Primitive& primitive : meshes[instance.mesh.index()].primitives) {
            triangles += triangleCount(*this, primitive);
        }
    }
    return triangles;
}

bool SceneData::drawsOnlyOpaqueStaticTriangles() const {
    for (const Instance& instance : instances) {
        if (nodes[instance.node.index()].skin) {
            return false;
        }
        for (const Primitive& primitive : meshes[instance.mesh.index()].primitives) {
            const Material& material = materials[primitive.material.index()];
            if (primitive.topology != Topology::TriangleList || !primitive.targets.empty() ||
                material.alphaMode != AlphaMode::Opaque || material.transmission) {
                return false;
            }
        }
    }
    return !instances.empty();
}

std::uint64_t triangleCount(Topology topology, std::uint64_t count) {
    switch (topology) {
        case Topology::TriangleList:
            return count / 3;
        case Topology::TriangleStrip:
            return count >= 3 ? count - 2 : 0;
        default:
            return 0;
    }
}

std::uint64_t triangleCount(const SceneData& scene, const Primitive& primitive) {
    return triangleCount(primitive.topology, primitive.indices
                                                 ? scene.accessors[primitive.indices->index()].count
                                                 : primitive.vertexCount);
}

}  // namespace encore::scene
