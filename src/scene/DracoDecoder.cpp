// KHR_draco_mesh_compression: the primitive's bufferView holds a Draco stream; its glTF accessors
// describe the decoded data but have no bytes. Each decoded attribute is written into the slot of
// the accessor that describes it (so the primitive keeps its accessor ids); an accessor already
// filled by another Draco primitive gets a fresh accessor recorded in dracoRemaps instead.

#include <algorithm>
#include <cstring>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

template <typename T>
bool convertAttribute(const draco::PointCloud& cloud,
                      const draco::PointAttribute& attribute,
                      int components,
                      std::vector<std::uint8_t>& bytes) {
    const std::size_t elementSize = sizeof(T) * components;
    bytes.resize(elementSize * cloud.num_points());
    T values[4] = {};
    for (draco::PointIndex::ValueType i = 0; i < cloud.num_points(); ++i) {
        const auto valueIndex = attribute.mapped_index(draco::PointIndex(i));
        if (!attribute.ConvertValue<T>(valueIndex, std::int8_t(components), values)) {
            return false;
        }
        std::memcpy(bytes.data() + i * elementSize, values, elementSize);
    }
    return true;
}

bool convertAttribute(const draco::PointCloud& cloud,
                      const draco::PointAttribute& attribute,
                      ComponentType type,
                      int components,
                      std::vector<std::uint8_t>& bytes) {
    switch (type) {
        case ComponentType::Int8:
            return convertAttribute<std::int8_t>(cloud, attribute, components, bytes);
        case ComponentType::Uint8:
            return convertAttribute<std::uint8_t>(cloud, attribute, components, bytes);
        case ComponentType::Int16:
            return convertAttribute<std::int16_t>(cloud, attribute, components, bytes);
        case ComponentType::Uint16:
            return convertAttribute<std::uint16_t>(cloud, attribute, components, bytes);
        case ComponentType::Uint32:
            return convertAttribute<std::uint32_t>(cloud, attribute, components, bytes);
        case ComponentType::Float32:
            return convertAttribute<float>(cloud, attribute, components, bytes);
    }
    return false;
}

// Stores a decoded accessor in the glTF accessor's slot, or appends it when the slot is taken.
void placeDecoded(LoadContext& context,
                  std::pair<std::size_t, std::size_t> primitive,
                  std::uint32_t gltfAccessor,
                  AccessorId decoded) {
    SceneData& scene = context.scene;
    if (gltfAccessor != kDracoIndicesKey && context.accessorDracoOnly[gltfAccessor] &&
        !context.accessorFilled[gltfAccessor]) {
        scene.accessors[gltfAccessor] = std::move(scene.accessors[decoded.index()]);
        scene.accessors.pop_back();
        context.accessorFilled[gltfAccessor] = true;
        return;
    }
    context.dracoRemaps[primitive][gltfAccessor] = decoded;
}

Result<void> decodePrimitive(LoadContext& context,
                             std::size_t meshIndex,
                             std::size_t primitiveIndex) {
    const GltfPrimitive& primitive = context.document.meshes[meshIndex].primitives[primitiveIndex];
    const GltfDracoCompression& draco = *primitive.draco;
    SceneData& scene = context.scene;
    const std::string name =
        "mesh " + std::to_string(meshIndex) + ", primitive " + std::to_string(primitiveIndex);

    const BufferView& view = scene.bufferViews[draco.bufferView];
    const auto& buffer = scene.buffers[view.buffer.index()].bytes;
    draco::DecoderBuffer stream;
    stream.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset),
                static_cast<std::size_t>(view.byteLength));
    const auto geometryType = draco::Decoder::GetEncodedGeometryType(&stream);
    if (!geometryType.ok()) {
        return makeError(ErrorCode::InvalidFormat, name + " cannot be decoded by Draco (" +
                                                       geometryType.status().error_msg_string() +
                                                       ").");
    }
    draco::Decoder decoder;
    std::unique_ptr<draco::PointCloud> cloud;
    const draco::Mesh* mesh = nullptr;
    if (geometryType.value() == draco::TRIANGULAR_MESH) {
        auto decoded = decoder.DecodeMeshFromBuffer(&stream);
        if (!decoded.ok()) {
            return makeError(ErrorCode::InvalidFormat, name + " cannot be decoded by Draco (" +
                                                           decoded.status().error_msg_string() +
                                                           ").");
        }
        std::unique_ptr<draco::Mesh> decodedMesh = std::move(decoded).value();
        mesh = decodedMesh.get();
        cloud = std::move(decodedMesh);
    } else {
        auto decoded = decoder.DecodePointCloudFromBuffer(&stream);
        if (!decoded.ok()) {
            return makeError(ErrorCode::InvalidFormat, name + " cannot be decoded by Draco (" +
                                                           decoded.status().error_msg_string() +
                                                           ").");
        }
        cloud = std::move(decoded).value();
    }
    const std::uint32_t pointCount = cloud->num_points();
    const auto key = std::pair{meshIndex, primitiveIndex};

    for (const auto& [semantic, uniqueId] : draco.attributes) {
        // Clang 14 cannot capture a structured binding in a lambda (C++20 allows it).
        const std::string& wanted = semantic;
        const auto gltf = std::find_if(primitive.attributes.begin(), primitive.attributes.end(),
                                       [&](const auto& entry) { return entry.first == wanted; });
        if (gltf == primitive.attributes.end()) {
            continue;  // The extension may carry attributes the primitive does not use.
        }
        const draco::PointAttribute* attribute = cloud->GetAttributeByUniqueId(uniqueId);
        if (!attribute) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " names Draco attribute " + std::to_string(uniqueId) + " for " +
                                 semantic + ", but the Draco data has no such attribute.");
        }
        const GltfAccessor& accessor = context.document.accessors[gltf->second];
        if (accessor.isMatrix) {
            return makeError(ErrorCode::InvalidFormat, name + " has a matrix " + semantic +
                                                           " attribute (accessor " +
                                                           std::to_string(gltf->second) + ").");
        }
        // Draco dequantises float attributes; integer ones keep the accessor's declared type.
        std::vector<std::uint8_t> bytes;
        const int components = static_cast<int>(accessor.componentCount);
        if (!convertAttribute(*cloud, *attribute, accessor.componentType, components, bytes)) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has a Draco attribute " + std::to_string(uniqueId) + " (" +
                                 semantic + ") that cannot be converted to its accessor's type.");
        }
        const AccessorId decoded = appendAccessor(scene, std::move(bytes), accessor.componentType,
                                                  std::uint8_t(components), accessor.normalized,
                                                  pointCount, "Draco " + semantic + " of " + name);
        scene.accessors[decoded.index()].min = accessor.min;
        scene.accessors[decoded.index()].max = accessor.max;
        placeDecoded(context, key, gltf->second, decoded);
    }

    if (mesh) {
        const std::uint64_t indexCount = std::uint64_t(mesh->num_faces()) * 3;
        const bool narrow = pointCount < 65536;
        std::vector<std::uint8_t> bytes(indexCount * (narrow ? 2 : 4));
        for (draco::FaceIndex::ValueType f = 0; f < mesh->num_faces(); ++f) {
            const auto& face = mesh->face(draco::FaceIndex(f));
            for (int corner = 0; corner < 3; ++corner) {
                const std::uint32_t value = face[corner].value();
                const std::size_t at = std::size_t(f) * 3 + corner;
                if (narrow) {
                    const auto narrowValue = static_cast<std::uint16_t>(value);
                    std::memcpy(bytes.data() + at * 2, &narrowValue, 2);
                } else {
                    std::memcpy(bytes.data() + at * 4, &value, 4);
                }
            }
        }
        const AccessorId decoded = appendAccessor(
            scene, std::move(bytes), narrow ? ComponentType::Uint16 : ComponentType::Uint32, 1,
            false, static_cast<std::uint32_t>(indexCount), "Draco indices of " + name);
        placeDecoded(context, key, primitive.indices.value_or(kDracoIndicesKey), decoded);
    }
    return {};
}

}  // namespace

Result<void> decodeDracoPrimitives(LoadContext& context) {
    context.scene.accessors.resize(context.document.accessors.size());
    const auto& meshes = context.document.meshes;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        for (std::size_t p = 0; p < meshes[m].primitives.size(); ++p) {
            if (meshes[m].primitives[p].draco) {
                ENCORE_TRY(decodePrimitive(context, m, p));
            }
        }
    }
    return {};
}

}  // namespace encore::scene
