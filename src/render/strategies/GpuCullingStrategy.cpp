#include "GpuCullingStrategy.h"

#include <cassert>
#include <map>

namespace encore::render {

Result<void> GpuCullingStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    mBundles = BundledFrame();
    mFirstPhaseBundle = BundledFrame();
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
                std::size_t draw = draws.size();
                if (mCullerCreated) {
                    const auto existing = drawOf.find({primitive.bindings, primitive.instances.first});
                    assert(existing != drawOf.end());
                    draw = existing->second;
                } else {
                    draws.push_back(culledDraw(primitive));
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
    auto culler = GpuCuller::create(setup, mInstances, setup.animation, std::move(bounds),
                                    std::move(draws));
    if (!culler) {
        return culler.error();
    }
    mCuller = std::move(*culler);
    mCullerCreated = true;
    return {};
}

CulledDraw GpuCullingStrategy::culledDraw(const PrimitiveDraw& primitive) const {
    const PrimitiveBindings& bindings = *primitive.bindings;
    CulledDraw draw;
    draw.instances = primitive.instances;
    draw.indexed = bindings.indices.has_value();
    draw.elementCount = bindings.indices ? bindings.indices->count : bindings.vertexCount;
    draw.topology = bindings.topology;
    // The coarser levels live in the index view after level 0 (scene::LevelOfDetail), which the
    // index binding reaches: each is a range of the same index buffer.
    const scene::SceneData& scene = *mScene;
    const scene::Mesh& mesh = scene.meshes[scene.instances[primitive.sceneInstance].mesh.value];
    const scene::Primitive& source = mesh.primitives[primitive.primitive];
    if (bindings.indices && source.indices) {
        const scene::Accessor& levelZero = scene.accessors[source.indices->value];
        for (const scene::LevelOfDetail& level : source.levels) {
            const scene::Accessor& indices = scene.accessors[level.indices.value];
            draw.coarserLevels.push_back(
                {static_cast<std::uint32_t>((indices.byteOffset - levelZero.byteOffset) /
                                            levelZero.elementSize()),
                 indices.count, level.error});
        }
    }
    return draw;
}

bool GpuCullingStrategy::drawsInTwoPhases(const FrameState& frame) const {
    // A frozen culling camera sees another view than the depth drawn: frustum culling only.
    return frame.culling.occlusion && !frame.cullingCamera;
}

void GpuCullingStrategy::beforePass(const wgpu::CommandEncoder& commands,
                                    const FrameState& frame) {
    CullingView view;
    view.camera = frame.cullingCamera.value_or(frame.camera);
    if (!frame.cullingCamera) {
        view.views = frame.views;
    }
    view.targetWidth = frame.targetWidth;
    view.targetHeight = frame.targetHeight;
    view.options = frame.culling;
    view.twoPhases = frame.phase == DrawPhase::First;
    mCuller.encodeFirstPhase(mQueue, commands, view, frame.timer);
    if (mUseBundles) {
        // Phase 1's draws, then phase 2's and the blended geometry: a frame of one pass replays
        // both (phase 2's counts stay zero), a two-phase frame one per pass.
        mFirstPhaseBundle.update(
            *mSetup, mMaterials->generation(), {},
            [this](RenderEncoder& encoder) { encodeCulled(encoder, 0); },
            [](RenderEncoder&, std::span<const std::uint32_t>) {});
        mBundles.update(
            *mSetup, mMaterials->generation(), blendOrder(frame.camera.position),
            [this](RenderEncoder& encoder) { encodeCulled(encoder, 1); },
            [this](RenderEncoder& encoder, std::span<const std::uint32_t> order) {
                setSharedBindGroups(encoder);
                encodeBlended(encoder, order);
            });
    }
}

void GpuCullingStrategy::betweenPhases(const wgpu::CommandEncoder& commands,
                                       const FrameState& frame, const wgpu::Texture& depth) {
    mCuller.encodeSecondPhase(commands, depth, frame.timer);
}

void GpuCullingStrategy::encodeCulled(RenderEncoder& encoder, std::uint32_t phase) const {
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
                const std::uint32_t levels = mCuller.draws()[primitive.draw].levelCount();
                for (std::uint32_t level = 0; level < levels; ++level) {
                    encoder.setBindGroup(1, mCuller.drawBindGroup(),
                                         mCuller.dynamicOffset(primitive.draw, level, phase));
                    const std::uint64_t offset = mCuller.argumentsOffset(primitive.draw, level, phase);
                    if (primitive.bindings->indices) {
                        encoder.drawIndexedIndirect(mCuller.indirectArguments(), offset);
                    } else {
                        encoder.drawIndirect(mCuller.indirectArguments(), offset);
                    }
                }
            }
        }
    }
}

void GpuCullingStrategy::encode(RenderEncoder& encoder, const FrameState& frame) const {
    if (mUseBundles) {
        if (frame.phase != DrawPhase::Second) {
            mFirstPhaseBundle.execute(encoder);
        }
        if (frame.phase != DrawPhase::First) {
            mBundles.execute(encoder);
        }
        return;
    }
    // A frame of one pass draws phase 1's records only: phase 2's counts stay zero.
    encodeCulled(encoder, frame.phase == DrawPhase::Second ? 1 : 0);
    if (frame.phase != DrawPhase::First && !mBlended.empty()) {
        setSharedBindGroups(encoder);  // Blended pipelines use the plain instance layout.
        encodeBlended(encoder, blendOrder(frame.camera.position));
    }
}

}  // namespace encore::render
