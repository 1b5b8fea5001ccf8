#include "render/VisibilityTables.h"

#include <algorithm>
#include <bit>
#include <optional>
#include <set>

#include "render/MaterialSlots.h"

namespace encore::render {

namespace {

// Word offsets in a primitive record (visibility_geometry.wgsl's k* constants).
constexpr std::uint32_t kIndexOffset = 0;
constexpr std::uint32_t kIndexSize = 1;
constexpr std::uint32_t kTriangleCount = 2;
constexpr std::uint32_t kMaterial = 3;
constexpr std::uint32_t kBin = 4;
constexpr std::uint32_t kDoubleSided = 5;
constexpr std::uint32_t kPosition = 6;
constexpr std::uint32_t kNormal = 9;
constexpr std::uint32_t kTexcoord0 = 12;
constexpr std::uint32_t kTexcoord1 = 15;
constexpr std::uint32_t kColor = 18;
constexpr std::uint32_t kTangent = 21;
constexpr std::uint32_t kBoundsCenter = 24;
constexpr std::uint32_t kBoundsExtent = 27;

std::uint32_t componentKind(scene::ComponentType type) {
    switch (type) {
        case scene::ComponentType::Int8:
            return 1;
        case scene::ComponentType::Uint8:
            return 2;
        case scene::ComponentType::Int16:
            return 3;
        case scene::ComponentType::Uint16:
            return 4;
        case scene::ComponentType::Uint32:
            return 5;
        case scene::ComponentType::Float32:
            return 6;
    }
    return 6;
}

// An attribute's three words (offset, stride, format), or nullopt when the shaders cannot reach
// its data (only a padded copy, another shared buffer, past the binding).
struct AttributeWords {
    std::uint32_t offset = 0;
    std::uint32_t stride = 0;
    std::uint32_t format = 0;
};

std::optional<AttributeWords> attributeWords(const GpuScene& scene,
                                             scene::AccessorId id,
                                             std::uint64_t maxGeometryBytes) {
    const auto placement = scene.geometry().sharedPlacement(id);
    if (!placement || placement->buffer != 0) {
        return std::nullopt;
    }
    const scene::Accessor& accessor = scene.data().accessors[id.index()];
    const std::uint64_t end =
        placement->byteOffset +
        (accessor.count == 0 ? 0 : std::uint64_t(accessor.count - 1) * accessor.byteStride) +
        accessor.elementSize();
    if (end > maxGeometryBytes) {
        return std::nullopt;
    }
    AttributeWords words;
    words.offset = std::uint32_t(placement->byteOffset);
    words.stride = accessor.byteStride;
    words.format = componentKind(accessor.componentType) |
                   (std::uint32_t(accessor.componentCount) << 8) |
                   (accessor.normalized ? 1u << 16 : 0u);
    return words;
}

bool animated(const GpuScene& scene, std::size_t mesh, std::size_t primitive) {
    if (!scene.animation()) {
        return false;
    }
    shaders::ShaderVariantKey key;
    scene.animation()->addVariantFlags(scene::MeshId(mesh), primitive, key);
    return key.animated();
}

// The primitive's record, or nullopt when the compute path cannot draw it.
std::optional<std::vector<std::uint32_t>> primitiveRecord(const GpuScene& scene,
                                                          std::size_t mesh,
                                                          std::size_t index,
                                                          std::uint64_t maxGeometryBytes) {
    const scene::SceneData& data = scene.data();
    const scene::Primitive& primitive = data.meshes[mesh].primitives[index];
    const scene::Material& material = data.materials[primitive.material.index()];
    if (primitive.topology != scene::Topology::TriangleList ||
        material.alphaMode != scene::AlphaMode::Opaque || material.transmission ||
        animated(scene, mesh, index)) {
        return std::nullopt;
    }
    // The fixed part and the mesh sphere (written by the caller).
    std::vector<std::uint32_t> record(VisibilityTables::kFirstLevel, 0);
    std::uint32_t triangles = primitive.vertexCount / 3;
    if (primitive.indices) {
        const auto indices = attributeWords(scene, *primitive.indices, maxGeometryBytes);
        if (!indices) {
            return std::nullopt;
        }
        record[kIndexOffset] = indices->offset;
        record[kIndexSize] = indices->stride;  // Index data is tightly packed.
        triangles = data.accessors[primitive.indices->index()].count / 3;
    }
    if (triangles == 0) {
        return std::nullopt;
    }
    record[kTriangleCount] = triangles;
    const bool tangent = materialUsesTangents(material) && !material.unlit &&
                         primitive.attribute(scene::Semantic::Tangent).has_value();
    record[kMaterial] = std::uint32_t(primitive.material.index());
    record[kBin] = std::uint32_t(primitive.material.index()) * 2 + (tangent ? 1 : 0);
    record[kDoubleSided] = material.doubleSided ? 1 : 0;
    // Attributes as mesh.wgsl's variant reads them: TEXCOORD_1 only where a texture reads it,
    // TANGENT only under a normal map.
    struct Wanted {
        scene::Semantic semantic;
        std::uint32_t offset;
        bool used;
    };
    const Wanted wanted[] = {
        {scene::Semantic::Position, kPosition, true},
        {scene::Semantic::Normal, kNormal, true},
        {scene::Semantic::Texcoord0, kTexcoord0, true},
        {scene::Semantic::Texcoord1, kTexcoord1, materialUsesTexcoord1(material)},
        {scene::Semantic::Color0, kColor, true},
        {scene::Semantic::Tangent, kTangent, tangent},
    };
    for (const Wanted& w : wanted) {
        const auto accessor = primitive.attribute(w.semantic);
        if (!accessor || !w.used) {
            if (w.semantic == scene::Semantic::Position) {
                return std::nullopt;
            }
            continue;
        }
        const auto words = attributeWords(scene, *accessor, maxGeometryBytes);
        if (!words) {
            return std::nullopt;
        }
        record[w.offset] = words->offset;
        record[w.offset + 1] = words->stride;
        record[w.offset + 2] = words->format;
    }
    glm::vec3 center(0.0f);
    glm::vec3 extent(1e30f);  // Empty bounds: never culled.
    if (!primitive.bounds.empty()) {
        center = (primitive.bounds.min + primitive.bounds.max) * 0.5f;
        extent = (primitive.bounds.max - primitive.bounds.min) * 0.5f;
    }
    for (int i = 0; i < 3; ++i) {
        record[kBoundsCenter + i] = std::bit_cast<std::uint32_t>(center[i]);
        record[kBoundsExtent + i] = std::bit_cast<std::uint32_t>(extent[i]);
    }
    // Coarser levels, while their indices lie where level 0's triangles can count to them.
    if (primitive.indices) {
        const std::uint32_t triangleBytes = record[kIndexSize] * 3;
        for (const scene::LevelOfDetail& level : primitive.levels) {
            const auto indices = attributeWords(scene, level.indices, maxGeometryBytes);
            if (!indices || indices->offset < record[kIndexOffset] ||
                (indices->offset - record[kIndexOffset]) % triangleBytes != 0) {
                break;
            }
            const std::uint32_t levelTriangles = data.accessors[level.indices.index()].count / 3;
            record.resize(VisibilityTables::kFirstLevel +
                          (record[VisibilityTables::kLevelCount] + 1) *
                              VisibilityTables::kLevelWords);
            std::uint32_t* words = &record[record.size() - VisibilityTables::kLevelWords];
            words[0] = (indices->offset - record[kIndexOffset]) / triangleBytes;
            words[1] = levelTriangles;
            words[2] = std::bit_cast<std::uint32_t>(level.error);
            ++record[VisibilityTables::kLevelCount];
        }
    }
    return record;
}

// The sphere GPU culling bounds an instance of `mesh` by (CullingBounds, unskinned): around all
// its primitives.
glm::vec4 meshSphere(const scene::Mesh& mesh) {
    scene::Bounds bounds;
    for (const scene::Primitive& primitive : mesh.primitives) {
        bounds.extend(primitive.bounds);
    }
    return bounds.empty() ? glm::vec4(0.0f) : glm::vec4(bounds.center(), bounds.radius());
}

}  // namespace

VisibilityTables buildVisibilityTables(const GpuScene& scene, std::uint64_t maxGeometryBytes) {
    const scene::SceneData& data = scene.data();
    VisibilityTables tables;
    tables.binCount = std::uint32_t(std::max<std::size_t>(data.materials.size(), 1) * 2);
    tables.computePath.resize(data.meshes.size());
    // Records first (their word offsets are known once the item count is).
    std::vector<std::vector<std::int64_t>> recordOf(data.meshes.size());
    std::vector<std::uint32_t> records;
    std::set<std::uint32_t> bins;
    for (std::size_t mesh = 0; mesh < data.meshes.size(); ++mesh) {
        const std::size_t count = data.meshes[mesh].primitives.size();
        tables.computePath[mesh].assign(count, false);
        recordOf[mesh].assign(count, -1);
        for (std::size_t index = 0; index < count; ++index) {
            auto record = primitiveRecord(scene, mesh, index, maxGeometryBytes);
            if (!record) {
                continue;
            }
            const glm::vec4 sphere = meshSphere(data.meshes[mesh]);
            for (int i = 0; i < 4; ++i) {
                (*record)[VisibilityTables::kMeshSphere + i] =
                    std::bit_cast<std::uint32_t>(sphere[i]);
            }
            tables.computePath[mesh][index] = true;
            recordOf[mesh][index] = std::int64_t(records.size());
            records.insert(records.end(), record->begin(), record->end());
        }
    }
    const InstanceBuffer& instances = scene.instances();
    std::vector<std::uint32_t> items;
    for (std::uint32_t slot = 0; slot < instances.size(); ++slot) {
        const scene::Instance& instance = data.instances[instances.instanceAt(slot)];
        const std::size_t mesh = instance.mesh.index();
        const bool mirrored = isMirrored(instance.world);
        for (std::size_t index = 0; index < recordOf[mesh].size(); ++index) {
            const std::int64_t record = recordOf[mesh][index];
            if (record < 0) {
                continue;
            }
            const std::uint32_t triangles = records[record + kTriangleCount];
            const std::uint32_t units = (triangles + VisibilityTables::kUnitTriangles - 1) /
                                        VisibilityTables::kUnitTriangles;
            items.insert(items.end(), {slot, std::uint32_t(record), units, mirrored ? 1u : 0u});
            tables.unitCount += units;
            tables.triangleCount += triangles;
            bins.insert(records[record + kBin]);
        }
    }
    tables.itemCount = std::uint32_t(items.size() / VisibilityTables::kItemWords);
    // Record offsets become word indices into `words`, after the items.
    const std::uint32_t recordBase = std::uint32_t(items.size());
    for (std::uint32_t item = 0; item < tables.itemCount; ++item) {
        items[item * VisibilityTables::kItemWords + 1] += recordBase;
    }
    tables.words = std::move(items);
    tables.words.insert(tables.words.end(), records.begin(), records.end());
    tables.bins.assign(bins.begin(), bins.end());
    return tables;
}

}  // namespace encore::render
