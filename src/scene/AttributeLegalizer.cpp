// Vertex attributes must match a WebGPU vertex format and a 4-byte aligned layout. Legal ones are
// left in place (the renderer binds the original bufferViews); the rest are copied once per
// accessor: 8/16-bit 1- and 3-component data is widened to 4 components, non-normalized integer
// data the shaders read as float (KHR_mesh_quantization positions, texcoords...) becomes float32.

#include <cstring>

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

enum class Fix { None, Repack, ToFloat };

bool isSmallInteger(ComponentType type) {
    return type != ComponentType::Float32 && type != ComponentType::Uint32;
}

Fix requiredFix(const SceneData& scene, const Accessor& accessor, Semantic semantic) {
    const bool joints = semantic == Semantic::Joints0 || semantic == Semantic::Joints1;
    if (accessor.componentType != ComponentType::Float32 && !accessor.normalized && !joints) {
        return Fix::ToFloat;
    }
    if (accessor.componentType == ComponentType::Uint32 && !joints) {
        return Fix::ToFloat;  // Normalized 32-bit integers have no vertex format.
    }
    if (isSmallInteger(accessor.componentType) &&
        (accessor.componentCount == 1 || accessor.componentCount == 3)) {
        return Fix::Repack;
    }
    const BufferView& view = scene.bufferViews[accessor.view.index()];
    if (accessor.byteStride % 4 != 0 || (view.byteOffset + accessor.byteOffset) % 4 != 0) {
        return Fix::Repack;  // WebGPU needs 4-byte aligned strides and buffer offsets.
    }
    return Fix::None;
}

AccessorId repack(SceneData& scene, AccessorId id, Semantic semantic, const std::string& name) {
    const Accessor source = scene.accessors[id.index()];
    const std::uint32_t size = componentSize(source.componentType);
    const std::uint8_t components =
        isSmallInteger(source.componentType) ? 4 : source.componentCount;
    const auto bytes = scene.accessorBytes(id);
    std::vector<std::uint8_t> packed(std::size_t(source.count) * size * components, 0);
    // A missing alpha means opaque; every other padded component reads as 0. Only small
    // integers gain a fourth component: float VEC3 colours are repacked (for alignment) as VEC3.
    const bool opaqueAlpha =
        semantic == Semantic::Color0 && source.componentCount == 3 && components == 4;
    const std::uint32_t one = source.componentType == ComponentType::Uint8    ? 0xFF
                              : source.componentType == ComponentType::Int8   ? 0x7F
                              : source.componentType == ComponentType::Uint16 ? 0xFFFF
                                                                              : 0x7FFF;
    for (std::size_t i = 0; i < source.count; ++i) {
        std::uint8_t* out = packed.data() + i * size * components;
        std::memcpy(out, bytes.data() + i * source.byteStride, source.elementSize());
        if (opaqueAlpha) {
            std::memcpy(out + 3 * size, &one, size);
        }
    }
    AccessorId result = appendAccessor(scene, std::move(packed), source.componentType, components,
                                       source.normalized, source.count, name);
    scene.accessors[result.index()].min = source.min;
    scene.accessors[result.index()].max = source.max;
    return result;
}

AccessorId toFloat(SceneData& scene, AccessorId id, const std::string& name) {
    const Accessor source = scene.accessors[id.index()];
    const auto values = scene.readFloats(id);
    const std::uint8_t components = source.componentCount;
    std::vector<std::uint8_t> packed(values.size() * components * sizeof(float));
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::memcpy(packed.data() + i * components * sizeof(float), &values[i][0],
                    components * sizeof(float));
    }
    AccessorId result = appendAccessor(scene, std::move(packed), ComponentType::Float32, components,
                                       false, source.count, name);
    if (!source.normalized) {
        // Integer-valued bounds are the same numbers in float.
        scene.accessors[result.index()].min = source.min;
        scene.accessors[result.index()].max = source.max;
    }
    return result;
}

}  // namespace

std::optional<Semantic> semanticFromName(std::string_view name) {
    static constexpr std::pair<std::string_view, Semantic> kNames[] = {
        {"POSITION", Semantic::Position},    {"NORMAL", Semantic::Normal},
        {"TANGENT", Semantic::Tangent},      {"TEXCOORD_0", Semantic::Texcoord0},
        {"TEXCOORD_1", Semantic::Texcoord1}, {"COLOR_0", Semantic::Color0},
        {"JOINTS_0", Semantic::Joints0},     {"WEIGHTS_0", Semantic::Weights0},
        {"JOINTS_1", Semantic::Joints1},     {"WEIGHTS_1", Semantic::Weights1},
    };
    for (const auto& [text, semantic] : kNames) {
        if (text == name) {
            return semantic;
        }
    }
    return std::nullopt;
}

Result<AccessorId> legalizeAttribute(LoadContext& context,
                                     Semantic semantic,
                                     AccessorId id,
                                     const std::string& what) {
    SceneData& scene = context.scene;
    const Accessor& accessor = scene.accessors[id.index()];
    if (accessor.componentCount < 1 || accessor.componentCount > 4) {
        return makeError(ErrorCode::InvalidFormat,
                         what + " has " + std::to_string(accessor.componentCount) +
                             " components per element; vertex attributes have 1 to 4.");
    }
    const bool needsVec3 = semantic == Semantic::Position || semantic == Semantic::Normal;
    if ((needsVec3 && accessor.componentCount != 3) ||
        (semantic == Semantic::Tangent && accessor.componentCount != 4)) {
        return makeError(ErrorCode::InvalidFormat,
                         what + " has " + std::to_string(accessor.componentCount) +
                             " components (" + std::string(semanticName(semantic)) + " needs " +
                             (needsVec3 ? "3" : "4") + ").");
    }
    const bool joints = semantic == Semantic::Joints0 || semantic == Semantic::Joints1;
    const bool weights = semantic == Semantic::Weights0 || semantic == Semantic::Weights1;
    if (joints && (accessor.componentCount != 4 || accessor.normalized ||
                   (accessor.componentType != ComponentType::Uint8 &&
                    accessor.componentType != ComponentType::Uint16))) {
        return makeError(ErrorCode::InvalidFormat,
                         what + " is not an unsigned byte or short VEC4 that is not normalised (" +
                             std::string(semanticName(semantic)) + " holds joint indices).");
    }
    if (weights &&
        (accessor.componentCount != 4 ||
         (accessor.componentType != ComponentType::Float32 &&
          !(accessor.normalized && (accessor.componentType == ComponentType::Uint8 ||
                                    accessor.componentType == ComponentType::Uint16))))) {
        return makeError(ErrorCode::InvalidFormat,
                         what + " is not a float or normalised unsigned byte or short VEC4 (" +
                             std::string(semanticName(semantic)) + " holds joint weights).");
    }
    const Fix fix = requiredFix(scene, accessor, semantic);
    if (fix == Fix::None) {
        return id;
    }
    // Primitives sharing an accessor share its legal copy.
    const auto key = std::pair{static_cast<std::uint32_t>(id.index()), semantic};
    if (const auto cached = context.legalCopies.find(key); cached != context.legalCopies.end()) {
        return cached->second;
    }
    const std::string name = std::string(fix == Fix::ToFloat ? "float32 copy of accessor "
                                                             : "4-byte aligned copy of accessor ") +
                             std::to_string(id.index());
    const AccessorId copy =
        fix == Fix::ToFloat ? toFloat(scene, id, name) : repack(scene, id, semantic, name);
    context.legalCopies.emplace(key, copy);
    return copy;
}

AccessorId gatherAccessor(SceneData& scene,
                          AccessorId id,
                          std::span<const std::uint32_t> corners,
                          const std::string& name) {
    const Accessor source = scene.accessors[id.index()];
    const auto bytes = scene.accessorBytes(id);
    const std::uint32_t elementSize = source.elementSize();
    const std::uint32_t stride = (elementSize + 3) / 4 * 4;
    std::vector<std::uint8_t> gathered(corners.size() * std::size_t(stride), 0);
    for (std::size_t i = 0; i < corners.size(); ++i) {
        std::memcpy(gathered.data() + i * stride,
                    bytes.data() + std::size_t(corners[i]) * source.byteStride, elementSize);
    }
    AccessorId result =
        appendAccessor(scene, std::move(gathered), source.componentType, source.componentCount,
                       source.normalized, static_cast<std::uint32_t>(corners.size()), name);
    Accessor& accessor = scene.accessors[result.index()];
    accessor.byteStride = stride;
    scene.bufferViews[accessor.view.index()].byteStride = stride;
    accessor.min = source.min;
    accessor.max = source.max;
    return result;
}

}  // namespace encore::scene
