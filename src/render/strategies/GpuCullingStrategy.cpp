#include "GpuCullingStrategy.h"

#include <cassert>
#include <map>

namespace encore::render {

namespace {

// Skinned and morphed instances are never culled: their geometry moves away from the mesh's
// bounds (joints, deltas) in ways the world matrix does not describe. A sphere of this radius
// around the origin passes every frustum plane test.
constexpr Sphere kUnbounded{0.0f, 0.0f, 0.0f, 1e30f};

bool deformed(const scene::SceneData& scene, const scene::Instance& instance) {
    if (scene.nodes[instance.node.index()].skin.has_value()) {
        return true;
    }
    for (const scene::Primitive& primitive : scene.meshes[instance.mesh.index()].primitives) {
        if (!primitive.targets.empty()) {
            return true;
        }
    }
    return false;
}

}  // namespace

Result<void> GpuCullingStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    mBundles = BundledFrame();
    mCulled.clear();
    mCullerCreated = false;
    return MaterialsStrategy::prepare(setup, scene);  // Calls groupDraws().
}

Result<void> GpuCullingStrategy::groupDraws() {
    ENCORE_TRY(MaterialsStrategy::groupDraws());
    const scene::SceneData& scene = *mScene;
    const RenderSetup& setup = *mSetup;
    // A regrouping (a material gained textures) keeps the culler and its draws, whose spheres
    // may have moved since: each primitive keeps its draw index.
    std::map<std::pair<const PrimitiveBindings*, std::uint32_t>, std::size_t> drawOf;
    for (const CulledPipeline& pipeline : mCulled) {
        for (const CulledMaterial& material : pipeline.materials) {
            for (const CulledPrimitive& primitive : material.primitives) {
                drawOf[{primitive.bindings, primitive.firstInstance}] = primitive.draw;
            }
        }
    }
    mCulled.clear();

    // Same grouping as `materials`; each draw becomes an indirect draw of the culled variant.
    std::vector<CulledDraw> draws;
    for (const PipelineGroup& group : mOpaque) {
        PipelineKey key = group.key;
        key.shader.instanceSource = shaders::InstanceSource::VisibleList;
        auto pipeline = mPipelines->get(key);
        if (!pipeline) {
            return pipeline.error();
        }
        CulledPipeline culled{*pipeline, key.shader, {}};
        for (const MaterialGroup& material : group.materials) {
            CulledMaterial culledMaterial{material.material, {}};
            for (const PrimitiveDraw& primitive : material.primitives) {
                const PrimitiveBindings& bindings = *primitive.bindings;
                std::size_t draw = draws.size();
                if (mCullerCreated) {
                    const auto existing = drawOf.find({primitive.bindings, primitive.instances.first});
                    assert(existing != drawOf.end());
                    draw = existing->second;
                } else {
                    draws.push_back({primitive.instances, bindings.indices.has_value(),
                                     bindings.indices ? bindings.indices->count
                                                      : bindings.vertexCount});
                }
                culledMaterial.primitives.push_back({primitive.bindings, primitive.instances.first,
                                                     draw, primitive.sceneInstance,
                                                     primitive.primitive});
            }
            culled.materials.push_back(std::move(culledMaterial));
        }
        mCulled.push_back(std::move(culled));
    }
    if (mCullerCreated) {
        return {};
    }

    mMeshBounds.assign(scene.meshes.size(), {});
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        for (const scene::Primitive& primitive : scene.meshes[mesh].primitives) {
            mMeshBounds[mesh].extend(primitive.bounds);
        }
    }
    std::vector<Sphere> spheres(mInstances.size());
    for (std::uint32_t slot = 0; slot < mInstances.size(); ++slot) {
        const scene::Instance& instance = scene.instances[mInstances.instanceAt(slot)];
        spheres[slot] = deformed(scene, instance)
                            ? kUnbounded
                            : worldSphere(mMeshBounds[instance.mesh.index()], instance.world);
    }
    auto culler = GpuCuller::create(setup, mInstances, std::move(spheres), std::move(draws));
    if (!culler) {
        return culler.error();
    }
    mCuller = std::move(*culler);
    mCullerCreated = true;
    return {};
}

void GpuCullingStrategy::beforePass(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame) {
    mCuller.encode(mQueue, commands, frame.cullingCamera.value_or(frame.camera), frame.timer);
    if (mUseBundles) {
        mBundles.update(
            *mSetup, mMaterials->generation(), blendOrder(frame.camera.position),
            [this](RenderEncoder& encoder) { encodeCulled(encoder); },
            [this](RenderEncoder& encoder, std::span<const std::uint32_t> order) {
                setSharedBindGroups(encoder);
                encodeBlended(encoder, order);
            });
    }
}

void GpuCullingStrategy::encodeCulled(RenderEncoder& encoder) const {
    encoder.setBindGroup(0, mFrameGroup);
    for (const CulledPipeline& group : mCulled) {
        encoder.setPipeline(group.pipeline);
        for (const CulledMaterial& material : group.materials) {
            encoder.setBindGroup(2, mMaterials->bindGroup(material.material));
            for (const CulledPrimitive& primitive : material.primitives) {
                if (group.shader.animated()) {
                    mAnimation->bind(encoder, group.shader, primitive.sceneInstance,
                                     primitive.primitive);
                }
                bindGeometry(encoder, *primitive.bindings);
                encoder.setBindGroup(1, mCuller.drawBindGroup(),
                                     mCuller.dynamicOffset(primitive.draw));
                const std::uint64_t offset = mCuller.argumentsOffset(primitive.draw);
                if (primitive.bindings->indices) {
                    encoder.drawIndexedIndirect(mCuller.indirectArguments(), offset);
                } else {
                    encoder.drawIndirect(mCuller.indirectArguments(), offset);
                }
            }
        }
    }
}

void GpuCullingStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    if (mUseBundles) {
        mBundles.execute(encoder);
        return;
    }
    encodeCulled(encoder);
    if (!mBlended.empty()) {
        setSharedBindGroups(encoder);  // Blended pipelines use the plain instance layout.
        encodeBlended(encoder, blendOrder(frame.camera.position));
    }
}

Result<void> GpuCullingStrategy::updateInstance(std::size_t instance, const glm::mat4& world) {
    ENCORE_TRY(MaterialsStrategy::updateInstance(instance, world));
    const scene::Instance& placed = mScene->instances[instance];
    mCuller.updateSphere(mQueue, mInstances.slotOf(instance),
                         deformed(*mScene, placed)
                             ? kUnbounded
                             : worldSphere(mMeshBounds[placed.mesh.index()], world));
    return {};
}

void GpuCullingStrategy::animateInstancesOnGpu(std::span<const std::uint32_t> instances) {
    for (const std::uint32_t instance : instances) {
        mCuller.updateSphere(mQueue, mInstances.slotOf(instance), kUnbounded);
    }
}

}  // namespace encore::render
