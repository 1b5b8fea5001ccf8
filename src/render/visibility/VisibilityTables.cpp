#include "render/visibility/VisibilityTables.h"

#include <algorithm>
#include <bit>
#include <cmath>
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

// Whether the loader's clusters cover the triangles [first, first + count) exactly, in order,
// each within a unit, with finite bounds.
bool coversLevel(const std::vector<scene::Cluster>& clusters,
                 std::uint32_t first,
                 std::uint32_t count) {
    std::uint64_t next = first;
    for (const scene::Cluster& cluster : clusters) {
        const auto finite3 = [](const glm::vec3& v) {
            return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
        };
        const bool finite = std::isfinite(cluster.radius) && std::isfinite(cluster.coneCutoff) &&
                            finite3(cluster.center) && finite3(cluster.coneApex) &&
                            finite3(cluster.coneAxis);
        if (cluster.firstTriangle != next || cluster.triangleCount == 0 ||
            cluster.triangleCount > VisibilityTables::kUnitTriangles || !finite) {
            return false;
        }
        next += cluster.triangleCount;
    }
    return !clusters.empty() && next == std::uint64_t(first) + count;
}

// The cluster records of a level of `count` triangles from `first`: the loader's clusters when
// they cover it, else runs of kUnitTriangles that nothing culls.
void appendClusters(std::vector<std::uint32_t>& words,
                    const std::vector<scene::Cluster>& clusters,
                    std::uint32_t first,
                    std::uint32_t count) {
    auto append = [&words](const scene::Cluster& cluster) {
        const float values[] = {cluster.center.x,   cluster.center.y,   cluster.center.z,
                                cluster.radius,     cluster.coneApex.x, cluster.coneApex.y,
                                cluster.coneApex.z, cluster.coneAxis.x, cluster.coneAxis.y,
                                cluster.coneAxis.z, cluster.coneCutoff};
        words.push_back(cluster.firstTriangle);
        words.push_back(cluster.triangleCount);
        for (float value : values) {
            words.push_back(std::bit_cast<std::uint32_t>(value));
        }
    };
    static_assert(VisibilityTables::kClusterWords == 13);
    if (coversLevel(clusters, first, count)) {
        for (const scene::Cluster& cluster : clusters) {
            append(cluster);
        }
        return;
    }
    for (std::uint32_t run = 0; run < count; run += VisibilityTables::kUnitTriangles) {
        scene::Cluster cluster;
        cluster.firstTriangle = first + run;
        cluster.triangleCount = std::min(VisibilityTables::kUnitTriangles, count - run);
        cluster.radius = VisibilityTables::kNeverCulled;
        cluster.coneCutoff = 2.0f;
        append(cluster);
    }
}

// A primitive's record and the cluster records of its levels; the record's cluster words
// count from the first of `clusters` (the caller moves them to the table's words).
struct PrimitiveWords {
    std::vector<std::uint32_t> record;
    std::vector<std::uint32_t> clusters;
    std::uint32_t mostClusters = 0;  // Of any level: the units an item of it may list.
    std::uint32_t clusterCount = 0;  // Of every level.
};

// Appends a level's clusters to `words` and writes where they lie into `place` (2 words).
void placeClusters(PrimitiveWords& words,
                   std::uint32_t place,
                   const std::vector<scene::Cluster>& clusters,
                   std::uint32_t first,
                   std::uint32_t count) {
    const auto before = std::uint32_t(words.clusters.size());
    appendClusters(words.clusters, clusters, first, count);
    const std::uint32_t added =
        (std::uint32_t(words.clusters.size()) - before) / VisibilityTables::kClusterWords;
    if (added == 1) {
        words.clusters[before + 1] |= VisibilityTables::kClusterAlone;
    }
    words.record[place] = before;
    words.record[place + 1] = added;
    words.mostClusters = std::max(words.mostClusters, added);
    words.clusterCount += added;
}

// The primitive's record, or nullopt when the compute path cannot draw it.
std::optional<PrimitiveWords> primitiveRecord(const GpuScene& scene,
                                              std::size_t mesh,
                                              std::size_t index,
                                              std::uint64_t maxGeometryBytes) {
    const scene::SceneData& data = scene.data();
    const scene::Primitive& primitive = data.meshes[mesh].primitives[index];
    // The material of the selected variant (KHR_materials_variants).
    const scene::MaterialId materialId = scene.materialOf(scene::MeshId(mesh), index);
    const scene::Material& material = data.materials[materialId.index()];
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
    record[kMaterial] = std::uint32_t(materialId.index());
    // Its own bin until assignShadingBins groups the materials (bit 0 stays the variant).
    record[kBin] = std::uint32_t(materialId.index()) * 2 + (tangent ? 1 : 0);
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
    PrimitiveWords words;
    words.record = std::move(record);
    std::vector<std::uint32_t>& fixed = words.record;
    placeClusters(words, VisibilityTables::kLevelClusters, primitive.clusters, 0, triangles);
    // Coarser levels, while their indices lie where level 0's triangles can count to them.
    if (primitive.indices) {
        const std::uint32_t triangleBytes = fixed[kIndexSize] * 3;
        for (const scene::LevelOfDetail& level : primitive.levels) {
            const auto indices = attributeWords(scene, level.indices, maxGeometryBytes);
            if (!indices || indices->offset < fixed[kIndexOffset] ||
                (indices->offset - fixed[kIndexOffset]) % triangleBytes != 0) {
                break;
            }
            const std::uint32_t levelTriangles = data.accessors[level.indices.index()].count / 3;
            const std::uint32_t first = (indices->offset - fixed[kIndexOffset]) / triangleBytes;
            const std::uint32_t base =
                VisibilityTables::kFirstLevel +
                fixed[VisibilityTables::kLevelCount] * VisibilityTables::kLevelWords;
            fixed.resize(base + VisibilityTables::kLevelWords);
            fixed[base] = first;
            fixed[base + 1] = levelTriangles;
            fixed[base + 2] = std::bit_cast<std::uint32_t>(level.error);
            placeClusters(words, base + 3, level.clusters, first, levelTriangles);
            ++fixed[VisibilityTables::kLevelCount];
        }
    }
    return words;
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
    std::vector<std::vector<std::uint32_t>> unitsOf(data.meshes.size());
    std::vector<std::vector<std::uint32_t>> clustersOf(data.meshes.size());
    std::vector<std::uint32_t> records;
    std::vector<std::uint32_t> clusters;
    // Where each record's cluster words are (word offsets in `records`), to be moved once the
    // clusters' place in the table is known.
    std::vector<std::uint32_t> clusterPointers;
    std::set<std::int64_t> usedRecords;
    for (std::size_t mesh = 0; mesh < data.meshes.size(); ++mesh) {
        const std::size_t count = data.meshes[mesh].primitives.size();
        tables.computePath[mesh].assign(count, false);
        recordOf[mesh].assign(count, -1);
        unitsOf[mesh].assign(count, 0);
        clustersOf[mesh].assign(count, 0);
        for (std::size_t index = 0; index < count; ++index) {
            auto primitive = primitiveRecord(scene, mesh, index, maxGeometryBytes);
            if (!primitive) {
                continue;
            }
            std::vector<std::uint32_t>& record = primitive->record;
            const glm::vec4 sphere = meshSphere(data.meshes[mesh]);
            for (int i = 0; i < 4; ++i) {
                record[VisibilityTables::kMeshSphere + i] = std::bit_cast<std::uint32_t>(sphere[i]);
            }
            // Cluster words counted from the start of all clusters.
            const auto recordStart = std::uint32_t(records.size());
            const auto clusterStart = std::uint32_t(clusters.size());
            record[VisibilityTables::kLevelClusters] += clusterStart;
            clusterPointers.push_back(recordStart + VisibilityTables::kLevelClusters);
            for (std::uint32_t level = 0; level < record[VisibilityTables::kLevelCount]; ++level) {
                const std::uint32_t place =
                    VisibilityTables::kFirstLevel + level * VisibilityTables::kLevelWords + 3;
                record[place] += clusterStart;
                clusterPointers.push_back(recordStart + place);
            }
            tables.computePath[mesh][index] = true;
            recordOf[mesh][index] = std::int64_t(records.size());
            unitsOf[mesh][index] = primitive->mostClusters;
            clustersOf[mesh][index] = primitive->clusterCount;
            records.insert(records.end(), record.begin(), record.end());
            clusters.insert(clusters.end(), primitive->clusters.begin(), primitive->clusters.end());
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
            items.insert(items.end(),
                         {slot, std::uint32_t(record), std::uint32_t(tables.clusterVisibilityWords),
                          mirrored ? 1u : 0u});
            tables.unitCount += unitsOf[mesh][index];
            tables.clusterVisibilityWords += clustersOf[mesh][index];
            tables.triangleCount += triangles;
            usedRecords.insert(record);
        }
    }
    tables.itemCount = std::uint32_t(items.size() / VisibilityTables::kItemWords);
    // Record offsets become word indices into `words`, after the items.
    const std::uint32_t recordBase = std::uint32_t(items.size());
    for (std::uint32_t item = 0; item < tables.itemCount; ++item) {
        items[item * VisibilityTables::kItemWords + 1] += recordBase;
    }
    // Cluster words become word indices too, after the records.
    const std::uint32_t clusterBase = recordBase + std::uint32_t(records.size());
    for (std::uint32_t pointer : clusterPointers) {
        records[pointer] += clusterBase;
    }
    tables.clusterCount = clusters.size() / VisibilityTables::kClusterWords;
    tables.words = std::move(items);
    tables.words.insert(tables.words.end(), records.begin(), records.end());
    tables.words.insert(tables.words.end(), clusters.begin(), clusters.end());
    for (const std::int64_t record : usedRecords) {
        tables.usedRecords.push_back(recordBase + std::uint32_t(record));
    }
    if (tables.clusterVisibilityWords <= VisibilityTables::kMaxStableUnits) {
        tables.unitTable.reserve(tables.clusterVisibilityWords * 2);
        for (std::uint32_t item = 0; item < tables.itemCount; ++item) {
            const std::uint32_t* words = &tables.words[item * VisibilityTables::kItemWords];
            const std::uint64_t end = item + 1 < tables.itemCount
                                          ? words[VisibilityTables::kItemWords + 2]
                                          : tables.clusterVisibilityWords;
            const std::uint32_t firstCluster =
                tables.words[words[1] + VisibilityTables::kLevelClusters];
            for (std::uint64_t unit = words[2]; unit < end; ++unit) {
                tables.unitTable.push_back(item);
                tables.unitTable.push_back(firstCluster + std::uint32_t(unit - words[2]) *
                                                              VisibilityTables::kClusterWords);
            }
        }
    }
    assignShadingBins(tables, MaterialBins(scene.materials()));
    return tables;
}

std::vector<std::uint32_t> assignShadingBins(VisibilityTables& tables, MaterialBins materialBins) {
    std::vector<std::uint32_t> changed;
    std::set<std::uint32_t> bins;
    for (const std::uint32_t record : tables.usedRecords) {
        std::uint32_t& word = tables.words[record + kBin];
        const bool tangent = (word & 1) != 0;
        const std::uint32_t assigned =
            materialBins.binWord(tables.words[record + kMaterial], tangent);
        if (assigned != word) {
            word = assigned;
            changed.push_back(record + kBin);
        }
        bins.insert(assigned & MaterialBins::kBinMask);
    }
    tables.bins.assign(bins.begin(), bins.end());
    tables.materialBins = std::move(materialBins);
    return changed;
}

}  // namespace encore::render
