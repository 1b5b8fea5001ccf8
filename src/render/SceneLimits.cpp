#include "render/SceneLimits.h"

#include <algorithm>
#include <set>
#include <string>

#include "render/BindGroupLayouts.h"
#include "render/Lighting.h"
#include "render/MaterialResources.h"

namespace encore::render {

namespace {

std::uint64_t roundUp(std::uint64_t value, std::uint64_t multiple) {
    return (value + multiple - 1) / multiple * multiple;
}

std::string describePrimitive(const scene::SceneData& scene,
                              std::size_t mesh,
                              std::size_t primitive) {
    const std::string& name = scene.meshes[mesh].name;
    return "mesh " + std::to_string(mesh) + (name.empty() ? "" : " ('" + name + "')") +
           ", primitive " + std::to_string(primitive);
}

// Every buffer the strategies make of a primitive's vertex and index data: `naive` copies each
// accessor; the others bind bufferViews where they lie and copy the attributes WebGPU cannot
// read in place (GeometryBuffers), whose padded copies are checked whichever way they end up.
Result<void> checkGeometry(const gpu::DeviceLimits& limits,
                           const scene::SceneData& scene,
                           StrategyKind kind) {
    std::set<std::uint32_t> checkedViews;
    std::set<std::uint32_t> checkedAccessors;
    auto checkAccessor = [&](scene::AccessorId id, bool index, const std::string& where,
                             std::string_view semantic) -> Result<void> {
        if (!id.valid() || id.index() >= scene.accessors.size()) {
            return {};  // The strategies report dangling references themselves.
        }
        const scene::Accessor& accessor = scene.accessors[id.index()];
        if (checkedAccessors.insert(id.value).second) {
            const std::uint64_t elementBytes =
                index ? accessor.elementSize() : roundUp(accessor.elementSize(), 4);
            ENCORE_TRY(gpu::checkBufferSize(limits, std::uint64_t(accessor.count) * elementBytes,
                                            "The " + std::string(semantic) + " data of " + where +
                                                " (accessor " + std::to_string(id.value) + ", " +
                                                std::to_string(accessor.count) + " elements)"));
        }
        if (kind != StrategyKind::Naive && accessor.view.valid() &&
            accessor.view.index() < scene.bufferViews.size() &&
            checkedViews.insert(accessor.view.value).second) {
            ENCORE_TRY(gpu::checkBufferSize(
                limits, roundUp(scene.bufferViews[accessor.view.index()].byteLength, 4),
                "BufferView " + std::to_string(accessor.view.value) +
                    " (vertex and index data of " + where + ")"));
        }
        return {};
    };
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        const auto& primitives = scene.meshes[mesh].primitives;
        for (std::size_t i = 0; i < primitives.size(); ++i) {
            const std::string where = describePrimitive(scene, mesh, i);
            for (const scene::VertexAttribute& attribute : primitives[i].attributes) {
                ENCORE_TRY(checkAccessor(attribute.accessor, false, where,
                                         scene::semanticName(attribute.semantic)));
            }
            if (primitives[i].indices) {
                ENCORE_TRY(checkAccessor(*primitives[i].indices, true, where, "index"));
            }
        }
    }
    return {};
}

bool usesInstanceStorage(StrategyKind kind) {
    return kind != StrategyKind::Naive && kind != StrategyKind::Layouts &&
           kind != StrategyKind::PipelineCache;
}

bool usesMaterials(StrategyKind kind) {
    return usesInstanceStorage(kind) && kind != StrategyKind::Instancing;
}

}  // namespace

Result<void> checkSceneWithinLimits(const gpu::DeviceLimits& limits,
                                    const scene::SceneData& scene,
                                    StrategyKind kind) {
    ENCORE_TRY(checkGeometry(limits, scene, kind));
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, std::uint64_t(scene.lightInstances.size()) * sizeof(LightUniform),
        "The punctual lights (" + std::to_string(scene.lightInstances.size()) + " placed)"));
    if (usesInstanceStorage(kind)) {
        const std::uint64_t instances = std::max<std::uint64_t>(scene.instances.size(), 1);
        ENCORE_TRY(gpu::checkStorageBinding(
            limits, instances * sizeof(TransformUniform),
            "The instance transforms of " + std::to_string(scene.instances.size()) +
                " instances (strategy " + std::string(strategyName(kind)) +
                " binds them as one storage buffer; naive, layouts and pipeline-cache do not)"));
    }
    // The animation storage buffers every strategy binds (AnimationBuffers): morph deltas
    // (position, normal, tangent as vec4 per target and vertex) and joint matrices with their
    // normal matrices.
    std::uint64_t deltas = 0;
    for (const scene::Mesh& mesh : scene.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            deltas += std::uint64_t(primitive.targets.size()) * primitive.vertexCount * 3;
        }
    }
    ENCORE_TRY(gpu::checkStorageBinding(
        limits, deltas * 16,
        "The morph target deltas (" + std::to_string(deltas / 3) + " target vertices)"));
    std::uint64_t joints = 0;
    for (const scene::Skin& skin : scene.skins) {
        joints += skin.joints.size();
    }
    ENCORE_TRY(gpu::checkStorageBinding(limits, joints * sizeof(TransformUniform),
                                        "The joint matrices of " +
                                            std::to_string(scene.skins.size()) + " skins (" +
                                            std::to_string(joints) + " joints)"));
    if (usesMaterials(kind)) {
        const std::uint64_t stride =
            roundUp(sizeof(MaterialUniform), std::max(limits.minUniformBufferOffsetAlignment, 4u));
        const std::uint64_t materials = std::max<std::uint64_t>(scene.materials.size(), 1);
        ENCORE_TRY(gpu::checkBufferSize(
            limits, materials * stride,
            "The uniforms of " + std::to_string(scene.materials.size()) + " materials"));
    }
    return {};
}

}  // namespace encore::render
