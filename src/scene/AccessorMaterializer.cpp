// Turns glTF accessors into SceneData accessors that always point at real bytes: the range of
// every accessor is checked against its bufferView, and accessors that have no bytes of their
// own in the file (no bufferView: zeros; sparse: base plus substitutions) are materialised.

#include <cstring>

#include "core/FileIO.h"
#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

// glTF element size; matrix columns of 1- and 2-byte components are padded to 4 bytes.
std::uint64_t gltfElementSize(const GltfAccessor& accessor) {
    const std::uint64_t component = componentSize(accessor.componentType);
    if (!accessor.isMatrix) {
        return component * accessor.componentCount;
    }
    const std::uint64_t columns = accessor.componentCount == 4   ? 2
                                  : accessor.componentCount == 9 ? 3
                                                                 : 4;
    return columns * ((columns * component + 3) / 4 * 4);
}

std::string bytesText(std::uint64_t bytes) {
    return std::to_string(bytes) + " bytes";
}

Accessor materialize(SceneData& scene,
                     std::vector<std::uint8_t> bytes,
                     ComponentType componentType,
                     std::uint8_t componentCount,
                     bool normalized,
                     std::uint32_t count,
                     std::uint32_t elementSize,
                     std::string bufferName) {
    BufferView view;
    view.buffer = BufferId(scene.buffers.size());
    view.byteLength = bytes.size();
    scene.buffers.push_back(Buffer{std::move(bufferName), std::move(bytes)});
    Accessor accessor;
    accessor.view = BufferViewId(scene.bufferViews.size());
    scene.bufferViews.push_back(view);
    accessor.count = count;
    accessor.componentType = componentType;
    accessor.componentCount = componentCount;
    accessor.normalized = normalized;
    accessor.byteStride = elementSize;
    return accessor;
}

Result<void> applySparse(const LoadContext& context,
                         const GltfAccessor& accessor,
                         const std::string& name,
                         std::uint64_t elementSize,
                         std::vector<std::uint8_t>& packed) {
    const GltfSparse& sparse = *accessor.sparse;
    const SceneData& scene = context.scene;
    if (sparse.count > accessor.count) {
        return makeError(ErrorCode::InvalidFormat, name +
                                                       " has more sparse values than elements (" +
                                                       std::to_string(sparse.count) + " > " +
                                                       std::to_string(accessor.count) + ").");
    }
    std::uint64_t indexSize = 0;
    switch (sparse.indicesComponentType) {
        case kGlUnsignedByte:
            indexSize = 1;
            break;
        case kGlUnsignedShort:
            indexSize = 2;
            break;
        case kGlUnsignedInt:
            indexSize = 4;
            break;
        default:
            return makeError(ErrorCode::InvalidFormat,
                             name + " has an invalid sparse indices componentType (" +
                                 std::to_string(sparse.indicesComponentType) + ").");
    }
    auto rangeOf = [&](std::uint32_t viewIndex, std::uint64_t offset, std::uint64_t size,
                       std::string_view part) -> Result<const std::uint8_t*> {
        const BufferView& view = scene.bufferViews[viewIndex];
        const auto end = mulAdd(1, offset, size);
        if (!end || *end > view.byteLength) {
            return makeError(
                ErrorCode::InvalidFormat,
                name + " has sparse " + std::string(part) + " reading past the end of bufferView " +
                    std::to_string(viewIndex) + " (offset " + std::to_string(offset) + " + " +
                    bytesText(size) + " > length " + std::to_string(view.byteLength) + ").");
        }
        return scene.buffers[view.buffer.index()].bytes.data() + view.byteOffset + offset;
    };
    // sparse.count <= accessor.count < 2^32 and sizes <= 64: these products cannot overflow.
    const std::uint8_t* indices = nullptr;
    ENCORE_TRY_ASSIGN(indices, rangeOf(sparse.indicesView, sparse.indicesOffset,
                                       sparse.count * indexSize, "indices"));
    const std::uint8_t* values = nullptr;
    ENCORE_TRY_ASSIGN(values, rangeOf(sparse.valuesView, sparse.valuesOffset,
                                      sparse.count * elementSize, "values"));
    for (std::uint64_t i = 0; i < sparse.count; ++i) {
        std::uint32_t index = 0;
        if (indexSize == 1) {
            index = indices[i];
        } else if (indexSize == 2) {
            std::uint16_t value;
            std::memcpy(&value, indices + i * 2, 2);
            index = value;
        } else {
            std::memcpy(&index, indices + i * 4, 4);
        }
        if (index >= accessor.count) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has sparse index " + std::to_string(index) +
                                 " (at position " + std::to_string(i) + ") out of range (count " +
                                 std::to_string(accessor.count) + ").");
        }
        std::memcpy(packed.data() + index * elementSize, values + i * elementSize, elementSize);
    }
    return {};
}

Result<Accessor> resolveAccessor(LoadContext& context, std::size_t index) {
    const GltfAccessor& source = context.document.accessors[index];
    SceneData& scene = context.scene;
    const std::string name = context.accessorName(index);
    if (source.count > 0xFFFFFFFFu) {
        return makeError(ErrorCode::LimitExceeded, name + " has too many elements (count " +
                                                       std::to_string(source.count) +
                                                       ", limit 4294967295).");
    }
    const std::uint64_t elementSize = gltfElementSize(source);
    const auto count = static_cast<std::uint32_t>(source.count);

    Accessor result;
    if (source.bufferView) {
        const BufferView& view = scene.bufferViews[*source.bufferView];
        const std::uint64_t stride = view.byteStride ? view.byteStride : elementSize;
        if (stride < elementSize) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has elements larger than the byteStride of bufferView " +
                                 std::to_string(*source.bufferView) + " (" +
                                 std::to_string(elementSize) + " > " + std::to_string(stride) +
                                 " bytes).");
        }
        const std::uint64_t span =
            count == 0 ? 0 : mulAdd(count - 1, stride, elementSize).value_or(0);
        const auto end = mulAdd(1, source.byteOffset, span);
        if (!end || *end > kMaxFileBytes) {
            return makeError(ErrorCode::LimitExceeded,
                             name + " is too large (count " + std::to_string(count) + " x stride " +
                                 std::to_string(stride) + " bytes from offset " +
                                 std::to_string(source.byteOffset) + " exceeds " +
                                 std::to_string(kMaxFileBytes) + " bytes).");
        }
        if (*end > view.byteLength) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " reads past the end of bufferView " +
                                 std::to_string(*source.bufferView) + " (offset " +
                                 std::to_string(source.byteOffset) + " + " + bytesText(span) +
                                 " > length " + std::to_string(view.byteLength) + ").");
        }
        result.view = BufferViewId(*source.bufferView);
        result.byteOffset = source.byteOffset;
        result.byteStride = static_cast<std::uint32_t>(stride);
    }
    result.count = count;
    result.componentType = source.componentType;
    result.componentCount = static_cast<std::uint8_t>(source.componentCount);
    result.normalized = source.normalized;
    result.min = source.min;
    result.max = source.max;
    if (source.bufferView && !source.sparse) {
        return result;
    }

    const auto packedSize = mulAdd(count, elementSize, 0);
    if (!packedSize || *packedSize > kMaxMaterializedBytes) {
        return makeError(ErrorCode::LimitExceeded,
                         name + " would need " + std::to_string(count) + " x " +
                             std::to_string(elementSize) +
                             " bytes, more than the 1 GiB materialisation limit (" +
                             std::to_string(kMaxMaterializedBytes) + " bytes).");
    }
    std::vector<std::uint8_t> packed(static_cast<std::size_t>(*packedSize), 0);
    if (source.bufferView) {
        const BufferView& view = scene.bufferViews[*source.bufferView];
        const std::uint8_t* base =
            scene.buffers[view.buffer.index()].bytes.data() + view.byteOffset + source.byteOffset;
        for (std::uint64_t i = 0; i < count; ++i) {
            std::memcpy(packed.data() + i * elementSize, base + i * result.byteStride, elementSize);
        }
    }
    if (source.sparse) {
        ENCORE_TRY(applySparse(context, source, name, elementSize, packed));
    }
    Accessor materialized =
        materialize(scene, std::move(packed), source.componentType, result.componentCount,
                    source.normalized, count, static_cast<std::uint32_t>(elementSize),
                    (source.sparse ? "sparse " : "zeros of ") + std::string("accessor ") +
                        std::to_string(index));
    materialized.min = source.min;
    materialized.max = source.max;
    return materialized;
}

}  // namespace

AccessorId appendAccessor(SceneData& scene,
                          std::vector<std::uint8_t> bytes,
                          ComponentType componentType,
                          std::uint8_t componentCount,
                          bool normalized,
                          std::uint32_t count,
                          std::string bufferName) {
    const auto elementSize = componentSize(componentType) * componentCount;
    Accessor accessor = materialize(scene, std::move(bytes), componentType, componentCount,
                                    normalized, count, elementSize, std::move(bufferName));
    scene.accessors.push_back(std::move(accessor));
    return AccessorId(scene.accessors.size() - 1);
}

Result<void> resolveAccessors(LoadContext& context) {
    const std::size_t count = context.document.accessors.size();
    context.scene.accessors.resize(std::max(context.scene.accessors.size(), count));
    for (std::size_t i = 0; i < count; ++i) {
        if (context.accessorFilled[i]) {
            continue;
        }
        if (context.document.accessors[i].count == 0) {
            return makeError(
                ErrorCode::InvalidFormat,
                context.accessorName(i) + " has count 0; glTF requires at least one element.");
        }
        Accessor accessor;
        ENCORE_TRY_ASSIGN(accessor, resolveAccessor(context, i));
        context.scene.accessors[i] = std::move(accessor);
    }
    return {};
}

}  // namespace encore::scene
