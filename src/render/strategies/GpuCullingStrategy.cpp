#include "GpuCullingStrategy.h"

#include <cassert>
#include <map>

#include "encore/render/RenderEncoder.h"

namespace encore::render {

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
                    const std::uint32_t elements =
                        bindings.indices ? bindings.indices->count : bindings.vertexCount;
                    draws.push_back(
                        {primitive.instances, bindings.indices.has_value(), elements,
                         static_cast<std::uint32_t>(triangleCount(bindings.topology, elements))});
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

    std::vector<std::size_t> instanceAt(mInstances.size());
    for (std::uint32_t slot = 0; slot < mInstances.size(); ++slot) {
        instanceAt[slot] = mInstances.instanceAt(slot);
    }
    CullingBounds bounds = CullingBounds::build(scene, instanceAt, setup.animation);
    auto culler = GpuCuller::create(setup, mInstances, std::move(bounds), std::move(draws));
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

}  // namespace encore::render
