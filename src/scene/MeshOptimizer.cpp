// optimizeMeshes: vertex-cache and vertex-fetch order, then the chain of levels of detail, for
// every indexed triangle list (the contract is in MeshOptimizer.h). Everything is checked before
// anything changes, so a failure leaves the scene as it was.

#include "scene/MeshOptimizer.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <unordered_map>

#include "core/Bytes.h"

namespace encore::scene {
namespace {

// Whether the primitive blends with its default material or any variant's.
bool mayBlend(const SceneData& scene, const Primitive& primitive) {
    const auto blends = [&scene](MaterialId material) {
        return material.index() < scene.materials.size() &&
               scene.materials[material.index()].alphaMode == AlphaMode::Blend;
    };
    return blends(primitive.material) ||
           std::any_of(primitive.variantMaterials.begin(), primitive.variantMaterials.end(),
                       [&](const VariantMapping& mapping) { return blends(mapping.material); });
}

constexpr std::uint64_t align4(std::uint64_t value) {
    return (value + 3) & ~std::uint64_t(3);
}

// 16-bit indices reach vertex 65534; 65535 is left out so that no index equals the strip
// restart value, should the data ever be drawn as a strip.
constexpr std::uint32_t kMaxUint16Vertices = 0xFFFF;

std::string primitiveName(std::size_t mesh, std::size_t primitive) {
    return "mesh " + std::to_string(mesh) + ", primitive " + std::to_string(primitive);
}

// meshoptimizer's time and memory grow with the index and vertex counts. Primitives past these
// are left as they are: one with more indices than any real asset's primitive has, and one that
// reads a small part of a large vertex buffer (a sub-mesh of a shared buffer, or hostile data
// declaring millions of vertices for one triangle), which would pay for the whole buffer.
constexpr std::uint32_t kMaxProcessedIndices = 1u << 26;
constexpr std::uint64_t kVerticesAlwaysProcessed = 1u << 16;
constexpr std::uint64_t kMaxVerticesPerIndex = 8;

// The primitives optimizeMeshes processes: indexed triangle lists within the limits above.
bool isProcessed(const Primitive& primitive, const SceneData& scene) {
    if (primitive.topology != Topology::TriangleList || !primitive.indices ||
        primitive.indices->index() >= scene.accessors.size()) {
        return false;
    }
    const std::uint32_t count = scene.accessors[primitive.indices->index()].count;
    return count >= 3 && count % 3 == 0 && count <= kMaxProcessedIndices &&
           primitive.vertexCount <=
               std::max(kVerticesAlwaysProcessed, kMaxVerticesPerIndex * count);
}

// Every accessor that holds one element per vertex of the primitive: attributes, then morph
// target deltas. An accessor may appear twice (TEXCOORD_0 and TEXCOORD_1 sharing one).
std::vector<AccessorId> vertexStreams(const Primitive& primitive) {
    std::vector<AccessorId> streams;
    for (const VertexAttribute& attribute : primitive.attributes) {
        streams.push_back(attribute.accessor);
    }
    for (const MorphTarget& target : primitive.targets) {
        for (const auto& delta : {target.position, target.normal, target.tangent}) {
            if (delta) {
                streams.push_back(*delta);
            }
        }
    }
    return streams;
}

// How many primitives read each accessor as a vertex stream: renumbering the vertices of a
// stream another primitive also reads would scramble that primitive.
std::unordered_map<AccessorId, std::uint32_t> streamReaders(const SceneData& scene) {
    std::unordered_map<AccessorId, std::uint32_t> readers;
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            std::vector<AccessorId> streams = vertexStreams(primitive);
            std::sort(streams.begin(), streams.end());
            streams.erase(std::unique(streams.begin(), streams.end()), streams.end());
            for (AccessorId stream : streams) {
                ++readers[stream];
            }
        }
    }
    return readers;
}

// The new data of all primitives: one scene buffer, views appended at 4-byte-aligned offsets.
class OutputBuffer {
  public:
    OutputBuffer(SceneData& scene, std::uint64_t reserveBytes) : mScene(scene) {
        mBuffer = BufferId(scene.buffers.size());
        scene.buffers.push_back(Buffer{"optimised meshes", {}});
        bytes().reserve(reserveBytes);
    }

    // A view of `length` bytes (zeros until written through data()); its offset is aligned to 4.
    BufferViewId appendView(std::uint64_t length, std::uint32_t byteStride) {
        const std::uint64_t offset = align4(bytes().size());
        bytes().resize(offset + length, 0);
        BufferView view;
        view.buffer = mBuffer;
        view.byteOffset = offset;
        view.byteLength = length;
        view.byteStride = byteStride;
        mScene.bufferViews.push_back(view);
        return BufferViewId(mScene.bufferViews.size() - 1);
    }

    std::uint8_t* data(BufferViewId view) {
        return bytes().data() + mScene.bufferViews[view.index()].byteOffset;
    }

  private:
    std::vector<std::uint8_t>& bytes() { return mScene.buffers[mBuffer.index()].bytes; }

    SceneData& mScene;
    BufferId mBuffer;
};

// A copy of `stream` with its elements in the order `remap` gives (remap[old] = new), tightly
// packed but with the stride rounded up to 4 bytes so WebGPU can bind it in place.
AccessorId remapStream(SceneData& scene,
                       OutputBuffer& output,
                       AccessorId stream,
                       const std::vector<std::uint32_t>& remap) {
    Accessor accessor = scene.accessors[stream.index()];
    const std::uint32_t elementSize = accessor.elementSize();
    const std::uint32_t stride = static_cast<std::uint32_t>(align4(elementSize));
    const std::vector<std::uint8_t> packed = scene.packedAccessorBytes(stream);
    std::vector<std::uint8_t> reordered(packed.size());
    meshopt_remapVertexBuffer(reordered.data(), packed.data(), accessor.count, elementSize,
                              remap.data());
    const BufferViewId view = output.appendView(std::uint64_t(stride) * accessor.count, stride);
    std::uint8_t* destination = output.data(view);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        std::memcpy(destination + i * stride, reordered.data() + i * elementSize, elementSize);
    }
    // The same values in another order: type, normalisation and min/max stay as they were.
    accessor.view = view;
    accessor.byteOffset = 0;
    accessor.byteStride = stride;
    scene.accessors.push_back(std::move(accessor));
    return AccessorId(scene.accessors.size() - 1);
}

// Renumbers the primitive's vertices in the order `indices` first reads them and rewrites
// `indices` and every vertex stream to match.
void renumberVertices(SceneData& scene,
                      OutputBuffer& output,
                      Primitive& primitive,
                      std::vector<std::uint32_t>& indices) {
    const std::uint32_t vertexCount = primitive.vertexCount;
    std::vector<std::uint32_t> remap(vertexCount);
    const std::size_t used =
        meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), vertexCount);
    // meshoptimizer drops vertices no triangle uses (~0u); keeping them, in their old order,
    // after the used ones keeps vertexCount, bounds and min/max what the loader made them.
    std::uint32_t next = static_cast<std::uint32_t>(used);
    bool identity = true;
    for (std::uint32_t v = 0; v < vertexCount; ++v) {
        if (remap[v] == ~0u) {
            remap[v] = next++;
        }
        identity = identity && remap[v] == v;
    }
    if (identity) {
        return;  // Already in fetch order: no copy of the streams needed.
    }
    for (std::uint32_t& index : indices) {
        index = remap[index];
    }
    std::map<AccessorId, AccessorId> copies;  // One copy per stream, however often it is used.
    auto replace = [&](AccessorId& stream) {
        auto [found, inserted] = copies.try_emplace(stream);
        if (inserted) {
            found->second = remapStream(scene, output, stream, remap);
        }
        stream = found->second;
    };
    for (VertexAttribute& attribute : primitive.attributes) {
        replace(attribute.accessor);
    }
    for (MorphTarget& target : primitive.targets) {
        for (std::optional<AccessorId>* delta :
             {&target.position, &target.normal, &target.tangent}) {
            if (*delta) {
                replace(**delta);
            }
        }
    }
}

struct SimplifiedLevel {
    std::vector<std::uint32_t> indices;
    float error = 0.0f;             // Object space.
    std::vector<Cluster> clusters;  // First triangles counted from the level's own first.
};

// The positions of the primitive's vertices, or nothing when there are fewer than its vertex
// count or some are not finite (meshoptimizer's quadrics and bounds turn those into garbage).
std::vector<glm::vec4> finitePositions(const SceneData& scene, const Primitive& primitive) {
    const auto positionAccessor = primitive.attribute(Semantic::Position);
    if (!positionAccessor) {
        return {};
    }
    std::vector<glm::vec4> positions = scene.readFloats(*positionAccessor);
    if (positions.size() < primitive.vertexCount ||
        !std::all_of(positions.begin(), positions.end(), [](const glm::vec4& p) {
            return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        })) {
        return {};
    }
    return positions;
}

// Clusters of at most Cluster::kMaxTriangles triangles (a workgroup's unit in the visibility
// strategy, whose triangle ids are unit * 256 + triangle) over at most 128 vertices: meshlets
// of about 200 triangles on a closed surface, small enough to cull a part of a large primitive,
// large enough to fill the strategy's 64-thread workgroups four triangles each. The cone weight
// trades a little compactness for normal cones narrow enough to cull back-facing clusters.
constexpr std::size_t kClusterVertices = 128;
constexpr float kClusterConeWeight = 0.25f;
static_assert(Cluster::kMaxTriangles <= 512 && Cluster::kMaxTriangles % 4 == 0,
              "meshopt_buildMeshlets' limits");
// meshopt_computeMeshletBounds multiplies coordinate differences: past this magnitude the
// products overflow a float, and its assertion on the NaN that follows aborts the process (a
// file found by encore_fuzz_load). Real assets lie far within it.
constexpr float kMaxClusterCoordinate = 1e9f;

}  // namespace

// A meshlet's local triangles index its vertex list in the source's order, so each triangle
// keeps its corners' order.
std::vector<Cluster> orderIntoClusters(std::vector<std::uint32_t>& indices,
                                       const std::vector<glm::vec4>& positions,
                                       bool scan) {
    const auto huge = [](const glm::vec4& p) {
        return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxClusterCoordinate;
    };
    if (indices.empty() || positions.empty() ||
        std::any_of(positions.begin(), positions.end(), huge)) {
        return {};
    }
    const std::size_t vertexCount = positions.size();
    const std::size_t bound =
        meshopt_buildMeshletsBound(indices.size(), kClusterVertices, Cluster::kMaxTriangles);
    std::vector<meshopt_Meshlet> meshlets(bound);
    std::vector<unsigned int> meshletVertices(bound * kClusterVertices);
    std::vector<unsigned char> meshletTriangles(bound * Cluster::kMaxTriangles * 3);
    const float* xyz = &positions[0].x;
    const std::size_t count =
        scan ? meshopt_buildMeshletsScan(meshlets.data(), meshletVertices.data(),
                                         meshletTriangles.data(), indices.data(), indices.size(),
                                         vertexCount, kClusterVertices, Cluster::kMaxTriangles)
             : meshopt_buildMeshlets(meshlets.data(), meshletVertices.data(),
                                     meshletTriangles.data(), indices.data(), indices.size(), xyz,
                                     vertexCount, sizeof(glm::vec4), kClusterVertices,
                                     Cluster::kMaxTriangles, kClusterConeWeight);
    std::vector<std::uint32_t> ordered;
    ordered.reserve(indices.size());
    std::vector<Cluster> clusters;
    clusters.reserve(count);
    for (std::size_t m = 0; m < count; ++m) {
        const meshopt_Meshlet& meshlet = meshlets[m];
        if (meshlet.triangle_count == 0) {
            continue;
        }
        Cluster cluster;
        cluster.firstTriangle = static_cast<std::uint32_t>(ordered.size() / 3);
        cluster.triangleCount = meshlet.triangle_count;
        const unsigned int* local = &meshletVertices[meshlet.vertex_offset];
        const unsigned char* corners = &meshletTriangles[meshlet.triangle_offset];
        for (std::size_t i = 0; i < std::size_t(meshlet.triangle_count) * 3; ++i) {
            ordered.push_back(local[corners[i]]);
        }
        const meshopt_Bounds bounds = meshopt_computeMeshletBounds(
            local, corners, meshlet.triangle_count, xyz, vertexCount, sizeof(glm::vec4));
        cluster.center = {bounds.center[0], bounds.center[1], bounds.center[2]};
        cluster.radius = bounds.radius;
        cluster.coneApex = {bounds.cone_apex[0], bounds.cone_apex[1], bounds.cone_apex[2]};
        cluster.coneAxis = {bounds.cone_axis[0], bounds.cone_axis[1], bounds.cone_axis[2]};
        cluster.coneCutoff = bounds.cone_cutoff;
        clusters.push_back(cluster);
    }
    if (ordered.size() != indices.size()) {
        return {};  // Some triangle left out (or repeated): keep the order the level had.
    }
    indices = std::move(ordered);
    return clusters;
}

namespace {

// In place. The FIFO variant models a 16-entry cache: smaller than today's GPUs keep, as
// meshoptimizer advises, so that the order does not thrash a cache that holds fewer vertices
// than expected.
void orderForVertexCache(std::vector<std::uint32_t>& indices,
                         std::size_t vertexCount,
                         VertexCacheOrder order) {
    if (order == VertexCacheOrder::Fast) {
        meshopt_optimizeVertexCacheFifo(indices.data(), indices.data(), indices.size(), vertexCount,
                                        16);
    } else {
        meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), vertexCount);
    }
}

// Halves the triangles of the previous level until a level no longer gets to half, comes out
// empty or the error budget is spent. Level k is simplified from level k-1 (far cheaper than
// from level 0 each time); its error relative to level 0 is at most the sum of the steps'
// errors, which is what it records, so errors never decrease and stay within the budget.
std::vector<SimplifiedLevel> simplifyChain(const SceneData& scene,
                                           const Primitive& primitive,
                                           const std::vector<std::uint32_t>& level0,
                                           const MeshOptimizerOptions& options,
                                           bool lockBorders,
                                           bool clustered) {
    const std::vector<glm::vec4> positions = finitePositions(scene, primitive);
    if (positions.empty()) {
        return {};
    }
    const float* xyz = &positions[0].x;
    const std::size_t stride = sizeof(glm::vec4);
    const float scale = meshopt_simplifyScale(xyz, primitive.vertexCount, stride);
    const unsigned int flags = lockBorders ? unsigned(meshopt_SimplifyLockBorder) : 0u;

    std::vector<SimplifiedLevel> levels;
    float spent = 0.0f;  // Relative error summed over the steps so far.
    while (true) {
        const std::vector<std::uint32_t>& previous =
            levels.empty() ? level0 : levels.back().indices;
        const std::size_t target = previous.size() / 3 / 2 * 3;
        const float budget = options.maxRelativeError - spent;
        if (target == 0 || !(budget > 0.0f)) {
            break;
        }
        std::vector<std::uint32_t> simplified(previous.size());
        float stepError = 0.0f;
        const std::size_t count =
            meshopt_simplify(simplified.data(), previous.data(), previous.size(), xyz,
                             primitive.vertexCount, stride, target, budget, flags, &stepError);
        if (count == 0 || count > target) {
            break;
        }
        simplified.resize(count);
        orderForVertexCache(simplified, primitive.vertexCount, options.vertexCacheOrder);
        std::vector<Cluster> clusters;
        if (clustered) {
            clusters = orderIntoClusters(simplified, positions,
                                         options.vertexCacheOrder == VertexCacheOrder::Fast);
        }
        spent += stepError;
        levels.push_back({std::move(simplified), spent * scale, std::move(clusters)});
    }
    return levels;
}

// Clusters with their first triangles moved from their level's first to level 0's.
std::vector<Cluster> shiftedClusters(std::vector<Cluster> clusters, std::uint64_t firstTriangle) {
    for (Cluster& cluster : clusters) {
        cluster.firstTriangle += static_cast<std::uint32_t>(firstTriangle);
    }
    return clusters;
}

// Writes level 0 and the levels into one new view, in the layout SceneData.h documents, and
// points the primitive at it (with the levels' clusters, counted from level 0's first index).
void writeIndexLevels(SceneData& scene,
                      OutputBuffer& output,
                      Primitive& primitive,
                      const std::vector<std::uint32_t>& level0,
                      std::vector<Cluster> level0Clusters,
                      std::vector<SimplifiedLevel>& levels) {
    const bool narrow = primitive.vertexCount <= kMaxUint16Vertices;
    const std::uint32_t indexSize = narrow ? 2 : 4;
    std::vector<std::uint64_t> offsets;
    std::uint64_t length = 0;
    // Each level starts at a whole triangle from level 0's first index (a multiple of 12 bytes:
    // 4-byte aligned as SceneData.h requires, and of 6 or 12 bytes per triangle), so that its
    // triangles can be counted from level 0's as the visibility strategy counts them.
    auto place = [&](std::size_t count) {
        offsets.push_back((length + 11) / 12 * 12);
        length = offsets.back() + count * indexSize;
    };
    place(level0.size());
    for (const SimplifiedLevel& level : levels) {
        place(level.indices.size());
    }
    const BufferViewId view = output.appendView(length, 0);
    std::uint8_t* bytes = output.data(view);

    auto append = [&](const std::vector<std::uint32_t>& indices, std::uint64_t offset) {
        if (narrow) {
            for (std::size_t i = 0; i < indices.size(); ++i) {
                const auto value = static_cast<std::uint16_t>(indices[i]);
                std::memcpy(bytes + offset + i * 2, &value, 2);
            }
        } else {
            copyBytes(bytes + offset, indices.data(), indices.size() * 4);
        }
        Accessor accessor;
        accessor.view = view;
        accessor.byteOffset = offset;
        accessor.count = static_cast<std::uint32_t>(indices.size());
        accessor.componentType = narrow ? ComponentType::Uint16 : ComponentType::Uint32;
        accessor.componentCount = 1;
        accessor.byteStride = indexSize;
        scene.accessors.push_back(std::move(accessor));
        return AccessorId(scene.accessors.size() - 1);
    };
    primitive.indices = append(level0, offsets[0]);
    primitive.clusters = std::move(level0Clusters);
    primitive.levels.clear();
    for (std::size_t k = 0; k < levels.size(); ++k) {
        primitive.levels.push_back(
            {append(levels[k].indices, offsets[k + 1]), levels[k].error,
             shiftedClusters(std::move(levels[k].clusters), offsets[k + 1] / (indexSize * 3))});
    }
}

// The checks the processing relies on, made before anything changes: readable indices below
// the vertex count. Returns the bytes the new data can take at most.
Result<std::uint64_t> checkPrimitive(const SceneData& scene,
                                     const Primitive& primitive,
                                     const std::string& name) {
    const AccessorId id = *primitive.indices;
    const std::vector<std::uint32_t> indices = scene.readIndices(id);
    if (indices.size() != scene.accessors[id.index()].count) {
        return makeError(ErrorCode::InvalidFormat, name + ": its indices (accessor " +
                                                       std::to_string(id.value) +
                                                       ") cannot be read from their bufferView.");
    }
    const auto beyond = std::find_if(indices.begin(), indices.end(),
                                     [&](std::uint32_t i) { return i >= primitive.vertexCount; });
    if (beyond != indices.end()) {
        return makeError(ErrorCode::InvalidFormat,
                         name + " has index value " + std::to_string(*beyond) + " at position " +
                             std::to_string(beyond - indices.begin()) +
                             ", out of range for its vertex count (" +
                             std::to_string(primitive.vertexCount) + ").");
    }
    // Level 0 plus levels that halve: fewer than twice level 0, plus alignment padding.
    std::uint64_t bytes = 2 * (indices.size() * 4 + 4) + 64 * 12;
    for (AccessorId stream : vertexStreams(primitive)) {
        if (stream.index() < scene.accessors.size()) {
            const Accessor& accessor = scene.accessors[stream.index()];
            bytes += align4(accessor.elementSize()) * accessor.count + 4;
        }
    }
    return bytes;
}

// Renumbering needs every stream readable with one element per vertex; otherwise (only a
// hand-built SceneData gets here) the vertex order is kept.
bool streamsRenumberable(const SceneData& scene,
                         const Primitive& primitive,
                         const std::unordered_map<AccessorId, std::uint32_t>& readers) {
    for (AccessorId stream : vertexStreams(primitive)) {
        if (stream.index() >= scene.accessors.size() || readers.at(stream) > 1) {
            return false;
        }
        const Accessor& accessor = scene.accessors[stream.index()];
        if (accessor.count != primitive.vertexCount || accessor.elementSize() > 256 ||
            scene.accessorBytes(stream).empty()) {
            return false;
        }
    }
    return true;
}

// Which buffers the primitives read: vertex streams, indices and levels.
std::vector<bool> buffersReadByPrimitives(const SceneData& scene) {
    std::vector<bool> read(scene.buffers.size(), false);
    auto mark = [&](AccessorId id) {
        if (id.index() < scene.accessors.size()) {
            const BufferViewId view = scene.accessors[id.index()].view;
            if (view.index() < scene.bufferViews.size() &&
                scene.bufferViews[view.index()].buffer.index() < read.size()) {
                read[scene.bufferViews[view.index()].buffer.index()] = true;
            }
        }
    };
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            for (AccessorId stream : vertexStreams(primitive)) {
                mark(stream);
            }
            if (primitive.indices) {
                mark(*primitive.indices);
            }
            for (const LevelOfDetail& level : primitive.levels) {
                mark(level.indices);
            }
        }
    }
    return read;
}

}  // namespace

Result<MeshOptimizerReport> optimizeMeshes(SceneData& scene, const MeshOptimizerOptions& options) {
    MeshOptimizerReport report;
    if (!options.optimizeVertexOrder && !options.buildLevelsOfDetail) {
        return report;
    }
    std::uint64_t reserve = 0;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        for (std::size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
            const Primitive& primitive = scene.meshes[m].primitives[p];
            if (isProcessed(primitive, scene)) {
                ENCORE_TRY_ASSIGN(const auto bytes,
                                  checkPrimitive(scene, primitive, primitiveName(m, p)));
                reserve += bytes;
            }
        }
    }
    if (reserve == 0) {
        return report;  // Nothing to process: no empty buffer appended either.
    }

    const auto readers = streamReaders(scene);
    const std::vector<bool> readBefore = buffersReadByPrimitives(scene);
    OutputBuffer output(scene, reserve);
    for (Mesh& mesh : scene.meshes) {
        for (Primitive& primitive : mesh.primitives) {
            if (!isProcessed(primitive, scene)) {
                continue;
            }
            std::vector<std::uint32_t> indices = scene.readIndices(*primitive.indices);
            // Blending depends on the order triangles are drawn in: keep it (under any material
            // variant). Clusters reorder triangles, so they come with the vertex order.
            const bool blends = mayBlend(scene, primitive);
            const bool clustered = options.optimizeVertexOrder && options.buildClusters && !blends;
            std::vector<Cluster> clusters;
            if (options.optimizeVertexOrder) {
                if (!blends) {
                    orderForVertexCache(indices, primitive.vertexCount, options.vertexCacheOrder);
                }
                if (clustered) {
                    // Before the vertices are renumbered, so that they follow the final order.
                    clusters =
                        orderIntoClusters(indices, finitePositions(scene, primitive),
                                          options.vertexCacheOrder == VertexCacheOrder::Fast);
                }
                const bool renumber = streamsRenumberable(scene, primitive, readers);
                if (renumber) {
                    renumberVertices(scene, output, primitive, indices);
                }
                if (renumber && !blends) {
                    ++report.primitivesReordered;
                } else {
                    ++report.primitivesIndicesOnly;
                }
            }
            std::vector<SimplifiedLevel> levels;
            if (options.buildLevelsOfDetail) {
                const bool lockBorders = options.lockSharedBorders && mesh.primitives.size() > 1;
                levels = simplifyChain(scene, primitive, indices, options, lockBorders, clustered);
                report.levelsBuilt += levels.size();
            }
            report.clustersBuilt += clusters.size();
            for (const SimplifiedLevel& level : levels) {
                report.clustersBuilt += level.clusters.size();
            }
            writeIndexLevels(scene, output, primitive, indices, std::move(clusters), levels);
        }
    }
    // Once every primitive reading a buffer has moved to new data, the buffer only holds memory
    // (a .glb's BIN chunk would double the geometry a batch keeps loaded): its bytes go.
    const std::vector<bool> readAfter = buffersReadByPrimitives(scene);
    for (std::size_t b = 0; b < readBefore.size(); ++b) {
        if (readBefore[b] && !readAfter[b]) {
            scene.buffers[b].bytes = {};
            ++report.buffersReleased;
        }
    }
    return report;
}

}  // namespace encore::scene
