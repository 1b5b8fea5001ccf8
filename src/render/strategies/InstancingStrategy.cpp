#include "render/strategies/InstancingStrategy.h"

#include <unordered_map>

#include "render/AnimationBuffers.h"

namespace encore::render {

Result<void> InstancingStrategy::prepare(const RenderSetup& setup, const GpuScene& gpuScene) {
    const scene::SceneData& scene = gpuScene.data();
    const InstanceBuffer& instances = gpuScene.instances();
    mScene = &gpuScene;
    mFrameGroup = setup.frame->bindGroup();
    mPipelines = strategyPipelineCache(setup, mOwnPipelines);
    mGroups.clear();

    shaders::ShaderVariantKey shader;
    shader.instanceSource = shaders::InstanceSource::InstanceStorage;
    std::unordered_map<PipelineKey, std::size_t, PipelineKeyHash> groupOfKey;
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        const InstanceRange range = instances.meshRange(scene::MeshId(mesh));
        if (range.count == 0) {
            continue;
        }
        const auto& primitives = scene.meshes[mesh].primitives;
        for (std::size_t index = 0; index < primitives.size(); ++index) {
            shaders::ShaderVariantKey variant = shader;
            const std::vector<scene::Semantic> semantics =
                unlitPrimitiveSemantics(gpuScene.animation(), scene::MeshId(mesh), index, variant);
            ENCORE_TRY_ASSIGN(auto bindings,
                              gpuScene.geometry().bind(primitives[index], semantics));
            const PipelineKey key = meshPipelineKey(setup, bindings, variant);
            auto [found, inserted] = groupOfKey.try_emplace(key, mGroups.size());
            if (inserted) {
                ENCORE_TRY_ASSIGN(auto pipeline, mPipelines->get(key));
                mGroups.push_back({pipeline, {}});
            }
            mGroups[found->second].primitives.push_back(
                {std::move(bindings), range, variant, instances.instanceAt(range.first), index});
        }
    }
    return {};
}

void InstancingStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.setBindGroup(0, mFrameGroup);
    encoder.setBindGroup(1, mScene->instances().bindGroup());
    for (const PipelineGroup& group : mGroups) {
        encoder.setPipeline(group.pipeline);
        for (const PrimitiveDraw& primitive : group.primitives) {
            if (primitive.shader.animated()) {
                mScene->animation()->bind(encoder, primitive.shader, primitive.sceneInstance,
                                          primitive.primitive);
            }
            bindGeometry(encoder, primitive.bindings);
            drawGeometry(encoder, primitive.bindings, primitive.instances.count,
                         primitive.instances.first);
        }
    }
}

}  // namespace encore::render
