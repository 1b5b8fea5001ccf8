// Turns glTF primitives into ones WebGPU can draw: attributes legalised, indices checked and
// made Uint16/Uint32, line loops and triangle fans rewritten, NORMAL always present (flat
// normals need one normal per triangle corner, so such primitives are de-indexed), bounds set.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "core/Bytes.h"
#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

constexpr std::uint32_t kModeLineLoop = 2;
constexpr std::uint32_t kModeTriangles = 4;
constexpr std::uint32_t kModeTriangleStrip = 5;
constexpr std::uint32_t kModeTriangleFan = 6;

Topology topologyOf(std::uint32_t mode) {
    constexpr Topology kTopologies[] = {
        Topology::PointList,    Topology::LineList,      Topology::LineStrip,   Topology::LineStrip,
        Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleList};
    return kTopologies[mode];
}

// One triangle-list corner per entry, from any triangle topology.
std::vector<std::uint32_t> triangleCorners(std::uint32_t mode,
                                           const std::vector<std::uint32_t>& vertices) {
    std::vector<std::uint32_t> corners;
    const std::size_t n = vertices.size();
    if (mode == kModeTriangles) {
        corners.assign(vertices.begin(), vertices.begin() + n / 3 * 3);
    } else if (mode == kModeTriangleStrip) {
        for (std::size_t i = 0; i + 2 < n; ++i) {
            // Odd triangles of a strip swap their first two corners to keep the winding.
            const bool odd = i % 2 == 1;
            corners.insert(corners.end(),
                           {vertices[odd ? i + 1 : i], vertices[odd ? i : i + 1], vertices[i + 2]});
        }
    } else if (mode == kModeTriangleFan) {
        for (std::size_t i = 1; i + 1 < n; ++i) {
            corners.insert(corners.end(), {vertices[0], vertices[i], vertices[i + 1]});
        }
    }
    return corners;
}

AccessorId appendIndices(SceneData& scene,
                         const std::vector<std::uint32_t>& values,
                         const std::string& name) {
    const std::uint32_t maxValue =
        values.empty() ? 0 : *std::max_element(values.begin(), values.end());
    // 0xFFFF would restart a Uint16 strip, so such data gets 32-bit indices.
    if (maxValue < 0xFFFF) {
        std::vector<std::uint8_t> bytes(values.size() * 2);
        for (std::size_t i = 0; i < values.size(); ++i) {
            const auto value = static_cast<std::uint16_t>(values[i]);
            std::memcpy(bytes.data() + i * 2, &value, 2);
        }
        return appendAccessor(scene, std::move(bytes), ComponentType::Uint16, 1, false,
                              static_cast<std::uint32_t>(values.size()), name);
    }
    std::vector<std::uint8_t> bytes(values.size() * 4);
    copyBytes(bytes.data(), values.data(), bytes.size());
    return appendAccessor(scene, std::move(bytes), ComponentType::Uint32, 1, false,
                          static_cast<std::uint32_t>(values.size()), name);
}

AccessorId appendVec3s(SceneData& scene,
                       const std::vector<glm::vec3>& values,
                       const std::string& name) {
    std::vector<std::uint8_t> bytes(values.size() * sizeof(glm::vec3));
    copyBytes(bytes.data(), values.data(), bytes.size());
    return appendAccessor(scene, std::move(bytes), ComponentType::Float32, 3, false,
                          static_cast<std::uint32_t>(values.size()), name);
}

float normalizeBound(float value, ComponentType type) {
    switch (type) {
        case ComponentType::Int8:
            return std::max(value / 127.0f, -1.0f);
        case ComponentType::Uint8:
            return value / 255.0f;
        case ComponentType::Int16:
            return std::max(value / 32767.0f, -1.0f);
        case ComponentType::Uint16:
            return value / 65535.0f;
        default:
            return value;
    }
}

Bounds positionBounds(const SceneData& scene, AccessorId position) {
    const Accessor& accessor = scene.accessors[position.index()];
    Bounds bounds;
    if (accessor.min.size() == 3 && accessor.max.size() == 3) {
        glm::vec3 min, max;
        for (int c = 0; c < 3; ++c) {
            min[c] = accessor.normalized ? normalizeBound(accessor.min[c], accessor.componentType)
                                         : accessor.min[c];
            max[c] = accessor.normalized ? normalizeBound(accessor.max[c], accessor.componentType)
                                         : accessor.max[c];
        }
        if (glm::all(glm::lessThanEqual(min, max)) && std::isfinite(min.x + min.y + min.z) &&
            std::isfinite(max.x + max.y + max.z)) {
            bounds.extend(min);
            bounds.extend(max);
            return bounds;
        }
    }
    for (const glm::vec4& value : scene.readFloats(position)) {
        if (std::isfinite(value.x + value.y + value.z)) {
            bounds.extend(glm::vec3(value));
        }
    }
    return bounds;
}

class PrimitiveConverter {
  public:
    PrimitiveConverter(LoadContext& context, std::size_t mesh, std::size_t primitive)
        : mContext(context),
          mScene(context.scene),
          mSource(context.document.meshes[mesh].primitives[primitive]),
          mKey(mesh, primitive),
          mName("mesh " + std::to_string(mesh) + ", primitive " + std::to_string(primitive)) {}

    Result<Primitive> convert();

  private:
    AccessorId resolve(std::uint32_t gltfAccessor) const {
        const auto remap = mContext.dracoRemaps.find(mKey);
        if (remap != mContext.dracoRemaps.end()) {
            if (const auto it = remap->second.find(gltfAccessor); it != remap->second.end()) {
                return it->second;
            }
        }
        return AccessorId(gltfAccessor);
    }
    Result<void> convertAttributes();
    Result<void> convertTargets();
    Result<void> readIndexValues();
    void generateFlatNormals(const std::vector<std::uint32_t>& vertices);

    LoadContext& mContext;
    SceneData& mScene;
    const GltfPrimitive& mSource;
    std::pair<std::size_t, std::size_t> mKey;
    std::string mName;
    Primitive mResult;
    std::optional<AccessorId> mIndexAccessor;
    std::optional<std::vector<std::uint32_t>> mIndexValues;
};

Result<void> PrimitiveConverter::convertAttributes() {
    std::optional<std::pair<std::string, std::uint32_t>> first;
    for (const auto& [name, gltfAccessor] : mSource.attributes) {
        const AccessorId id = resolve(gltfAccessor);
        const std::uint32_t count = mScene.accessors[id.index()].count;
        if (!first) {
            first = std::pair{name, count};
        } else if (count != first->second) {
            return makeError(ErrorCode::InvalidFormat,
                             mName + " has attributes of different lengths (" + first->first +
                                 " has " + std::to_string(first->second) + " elements, " + name +
                                 " has " + std::to_string(count) + ").");
        }
        const auto semantic = semanticFromName(name);
        if (!semantic) {
            continue;  // Custom and extra attributes are not drawn.
        }
        AccessorId legal;
        ENCORE_TRY_ASSIGN(
            legal, legalizeAttribute(mContext, *semantic, id, mContext.accessorName(gltfAccessor)));
        mResult.attributes.push_back(VertexAttribute{*semantic, legal});
    }
    std::sort(mResult.attributes.begin(), mResult.attributes.end(),
              [](const auto& a, const auto& b) { return a.semantic < b.semantic; });
    if (!mResult.attribute(Semantic::Position)) {
        return makeError(ErrorCode::InvalidFormat, mName + " has no POSITION attribute.");
    }
    mResult.vertexCount = first->second;
    return {};
}

// Morph targets: POSITION, NORMAL and TANGENT deltas as Float32 VEC3 accessors of the
// primitive's vertex count (integer ones, from KHR_mesh_quantization, converted once). Other
// target attributes (TEXCOORD_n, COLOR_n) are not animated and are skipped.
Result<void> PrimitiveConverter::convertTargets() {
    for (std::size_t t = 0; t < mSource.targets.size(); ++t) {
        MorphTarget target;
        for (const auto& [name, gltfAccessor] : mSource.targets[t]) {
            std::optional<AccessorId>* slot = name == "POSITION"  ? &target.position
                                              : name == "NORMAL"  ? &target.normal
                                              : name == "TANGENT" ? &target.tangent
                                                                  : nullptr;
            if (!slot) {
                continue;
            }
            const AccessorId id = resolve(gltfAccessor);
            const Accessor& accessor = mScene.accessors[id.index()];
            const std::string what = mName + ", morph target " + std::to_string(t) + " " + name +
                                     " (accessor " + std::to_string(gltfAccessor) + ")";
            if (accessor.count != mResult.vertexCount) {
                return makeError(ErrorCode::InvalidFormat,
                                 what + " has " + std::to_string(accessor.count) +
                                     " elements, but the primitive has " +
                                     std::to_string(mResult.vertexCount) + " vertices.");
            }
            if (accessor.componentCount != 3 || (accessor.componentType == ComponentType::Uint32) ||
                mContext.document.accessors[gltfAccessor].isMatrix) {
                return makeError(ErrorCode::InvalidFormat,
                                 what + " is not a VEC3 of floats or of 8- or 16-bit integers.");
            }
            if (accessor.componentType == ComponentType::Float32) {
                *slot = id;
                continue;
            }
            auto cached = mContext.morphCopies.find(id);
            if (cached == mContext.morphCopies.end()) {
                std::vector<std::uint8_t> bytes(std::size_t(accessor.count) * 12);
                const auto values = mScene.readFloats(id);
                for (std::size_t i = 0; i < values.size(); ++i) {
                    std::memcpy(bytes.data() + i * 12, &values[i][0], 12);
                }
                const AccessorId copy = appendAccessor(
                    mScene, std::move(bytes), ComponentType::Float32, 3, false, mResult.vertexCount,
                    "float32 copy of accessor " + std::to_string(gltfAccessor));
                cached = mContext.morphCopies.emplace(id, copy).first;
            }
            *slot = cached->second;
        }
        mResult.targets.push_back(target);
    }
    return {};
}

Result<void> PrimitiveConverter::readIndexValues() {
    std::optional<AccessorId> id;
    if (mSource.indices) {
        id = resolve(*mSource.indices);
    } else if (const auto remap = mContext.dracoRemaps.find(mKey);
               remap != mContext.dracoRemaps.end() && remap->second.count(kDracoIndicesKey)) {
        id = remap->second.at(kDracoIndicesKey);
    }
    if (!id) {
        return {};
    }
    const Accessor& accessor = mScene.accessors[id->index()];
    const auto type = accessor.componentType;
    if (accessor.componentCount != 1 ||
        (type != ComponentType::Uint8 && type != ComponentType::Uint16 &&
         type != ComponentType::Uint32)) {
        return makeError(ErrorCode::InvalidFormat,
                         mName + " has indices (accessor " + std::to_string(id->index()) +
                             ") that are not unsigned 8-, 16- or 32-bit scalars.");
    }
    auto values = mScene.readIndices(*id);
    // glTF forbids the primitive-restart value (all bits set) in index data; WebGPU would
    // restart a strip there, so convert() widens such 16-bit strip indices to 32 bits.
    // A 32-bit 0xFFFFFFFF is never below the vertex count: the range check below refuses it.
    const std::uint32_t restart = type == ComponentType::Uint8 ? 0xFFu : 0xFFFFu;
    if (const auto found = std::find(values.begin(), values.end(), restart);
        type != ComponentType::Uint32 && found != values.end()) {
        ENCORE_TRY(
            mContext.warn(ErrorCode::InvalidFormat,
                          mName + " has the primitive-restart value " + std::to_string(restart) +
                              " in its indices (accessor " + std::to_string(id->index()) +
                              ", position " + std::to_string(found - values.begin()) +
                              "), which glTF forbids; it is drawn as an ordinary vertex index."));
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] >= mResult.vertexCount) {
            return makeError(ErrorCode::InvalidFormat,
                             mName + " has index value " + std::to_string(values[i]) +
                                 " at position " + std::to_string(i) +
                                 ", out of range for its vertex count (" +
                                 std::to_string(mResult.vertexCount) + ").");
        }
    }
    mIndexAccessor = id;
    mIndexValues = std::move(values);
    return {};
}

void PrimitiveConverter::generateFlatNormals(const std::vector<std::uint32_t>& vertices) {
    const auto corners = triangleCorners(mSource.mode, vertices);
    const auto positions = mScene.readFloats(*mResult.attribute(Semantic::Position));
    std::vector<glm::vec3> normals(corners.size());
    for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
        const glm::vec3 a(positions[corners[t]]);
        const glm::vec3 b(positions[corners[t + 1]]);
        const glm::vec3 c(positions[corners[t + 2]]);
        glm::vec3 normal = glm::cross(b - a, c - a);
        const float length = glm::length(normal);
        // Degenerate triangles cover no pixels; a zero normal keeps NaNs out of the data.
        normal = (length > 0.0f && std::isfinite(length)) ? normal / length : glm::vec3(0.0f);
        normals[t] = normals[t + 1] = normals[t + 2] = normal;
    }
    for (VertexAttribute& attribute : mResult.attributes) {
        attribute.accessor = gatherAccessor(
            mScene, attribute.accessor, corners,
            "de-indexed " + std::string(semanticName(attribute.semantic)) + " of " + mName);
    }
    mResult.attributes.push_back(VertexAttribute{
        Semantic::Normal, appendVec3s(mScene, normals, "flat normals of " + mName)});
    for (std::size_t t = 0; t < mResult.targets.size(); ++t) {
        for (std::optional<AccessorId>* slot :
             {&mResult.targets[t].position, &mResult.targets[t].normal,
              &mResult.targets[t].tangent}) {
            if (*slot) {
                *slot =
                    gatherAccessor(mScene, **slot, corners,
                                   "de-indexed morph target " + std::to_string(t) + " of " + mName);
            }
        }
    }
    mResult.topology = Topology::TriangleList;
    mResult.vertexCount = static_cast<std::uint32_t>(corners.size());
    mResult.indices.reset();
}

Result<Primitive> PrimitiveConverter::convert() {
    if (mSource.mode > kModeTriangleFan) {
        return makeError(ErrorCode::InvalidFormat,
                         mName + " has an unknown mode (" + std::to_string(mSource.mode) + ").");
    }
    ENCORE_TRY(convertAttributes());
    ENCORE_TRY(convertTargets());
    ENCORE_TRY(readIndexValues());
    const AccessorId position = *mResult.attribute(Semantic::Position);
    mResult.bounds = positionBounds(mScene, position);
    mResult.topology = topologyOf(mSource.mode);
    mResult.material = mSource.material ? MaterialId(*mSource.material) : defaultMaterial(mScene);
    ENCORE_TRY_ASSIGN(mResult.variantMaterials, convertVariantMappings(mSource, mName));

    const bool triangles = mSource.mode >= kModeTriangles;
    auto vertexList = [&] {
        if (mIndexValues) {
            return *mIndexValues;
        }
        std::vector<std::uint32_t> sequence(mResult.vertexCount);
        std::iota(sequence.begin(), sequence.end(), 0u);
        return sequence;
    };
    if (!mResult.attribute(Semantic::Normal)) {
        if (triangles) {
            generateFlatNormals(vertexList());
            std::sort(mResult.attributes.begin(), mResult.attributes.end(),
                      [](const auto& a, const auto& b) { return a.semantic < b.semantic; });
            return std::move(mResult);
        }
        // Points and lines are drawn unlit: a zero normal says so to the shader.
        const std::vector<glm::vec3> zeros(mResult.vertexCount, glm::vec3(0.0f));
        mResult.attributes.push_back(VertexAttribute{
            Semantic::Normal, appendVec3s(mScene, zeros, "zero normals of " + mName)});
        std::sort(mResult.attributes.begin(), mResult.attributes.end(),
                  [](const auto& a, const auto& b) { return a.semantic < b.semantic; });
    }

    bool rewrite = false;
    if (mSource.mode == kModeLineLoop) {
        auto loop = vertexList();
        if (!loop.empty()) {
            loop.push_back(loop.front());  // The closing segment of the loop.
        }
        mIndexValues = std::move(loop);
        rewrite = true;
    } else if (mSource.mode == kModeTriangleFan) {
        mIndexValues = triangleCorners(mSource.mode, vertexList());
        rewrite = true;
    }
    if (!mIndexValues) {
        return std::move(mResult);
    }
    if (!rewrite) {
        const Accessor& accessor = mScene.accessors[mIndexAccessor->index()];
        const std::uint32_t size = componentSize(accessor.componentType);
        const BufferView& view = mScene.bufferViews[accessor.view.index()];
        const bool strip =
            mResult.topology == Topology::LineStrip || mResult.topology == Topology::TriangleStrip;
        const bool restartValue =
            strip && accessor.componentType == ComponentType::Uint16 &&
            std::find(mIndexValues->begin(), mIndexValues->end(), 0xFFFFu) != mIndexValues->end();
        rewrite = accessor.componentType == ComponentType::Uint8 || accessor.byteStride != size ||
                  (view.byteOffset + accessor.byteOffset) % size != 0 || restartValue;
    }
    mResult.indices =
        rewrite ? appendIndices(mScene, *mIndexValues, "indices of " + mName) : *mIndexAccessor;
    return std::move(mResult);
}

}  // namespace

Result<void> convertMeshes(LoadContext& context) {
    const auto& meshes = context.document.meshes;
    context.scene.meshes.reserve(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        Mesh mesh;
        mesh.name = meshes[m].name;
        if (meshes[m].primitives.empty()) {
            ENCORE_TRY(context.warn(ErrorCode::InvalidFormat,
                                    "mesh " + std::to_string(m) +
                                        " has no primitives (glTF requires at least one); it "
                                        "draws nothing."));
        }
        for (std::size_t p = 0; p < meshes[m].primitives.size(); ++p) {
            const GltfPrimitive& source = meshes[m].primitives[p];
            const bool hasPosition =
                std::any_of(source.attributes.begin(), source.attributes.end(),
                            [](const auto& attribute) { return attribute.first == "POSITION"; });
            if (!hasPosition) {
                // The specification says clients should skip such primitives.
                ENCORE_TRY(context.warn(ErrorCode::InvalidFormat,
                                        "mesh " + std::to_string(m) + ", primitive " +
                                            std::to_string(p) +
                                            " has no POSITION attribute; it is skipped."));
                continue;
            }
            ENCORE_TRY(context.checkCancelled());
            Primitive primitive;
            ENCORE_TRY_ASSIGN(primitive, PrimitiveConverter(context, m, p).convert());
            mesh.primitives.push_back(std::move(primitive));
        }
        // glTF: every primitive of a mesh has the same number of morph targets.
        const auto& primitives = meshes[m].primitives;
        const std::size_t targets = primitives.empty() ? 0 : primitives.front().targets.size();
        for (std::size_t p = 1; p < primitives.size(); ++p) {
            if (primitives[p].targets.size() != targets) {
                return makeError(ErrorCode::InvalidFormat,
                                 "mesh " + std::to_string(m) + ", primitive " + std::to_string(p) +
                                     " has " + std::to_string(primitives[p].targets.size()) +
                                     " morph targets, but primitive 0 has " +
                                     std::to_string(targets) +
                                     " (glTF requires the same number in every primitive).");
            }
        }
        mesh.weights.assign(targets, 0.0f);
        // Weights on a mesh without morph targets have nothing to weigh: ignored.
        if (const auto& weights = meshes[m].weights; weights && targets > 0) {
            if (weights->size() != targets) {
                return makeError(ErrorCode::InvalidFormat,
                                 "mesh " + std::to_string(m) + " has " +
                                     std::to_string(weights->size()) + " default weights, but " +
                                     std::to_string(targets) + " morph targets.");
            }
            mesh.weights = *weights;
        }
        context.scene.meshes.push_back(std::move(mesh));
    }
    return {};
}

}  // namespace encore::scene
