#include "render/strategies/PipelineCacheStrategy.h"

#include <unordered_map>

#include "render/AnimationBuffers.h"

namespace encore::render {

Result<void> PipelineCacheStrategy::prepare(const RenderSetup& setup, const GpuScene& gpuScene) {
    const scene::SceneData& scene = gpuScene.data();
    ENCORE_TRY(NodeUniforms::checkLimit(scene, setup.mappingBudget, strategyName(kind())));
    mFrameGroup = setup.frame->bindGroup();
    mAnimation = gpuScene.animation();
    mPipelines = std::make_unique<PipelineCache>(setup);
    mGroups.clear();

    std::vector<std::vector<std::size_t>> nodesOfMesh(scene.meshes.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        nodesOfMesh[scene.instances[i].mesh.index()].push_back(i);
    }
    // Groups in first-use order; a pipeline's group found through its key.
    std::unordered_map<PipelineKey, std::size_t, PipelineKeyHash> groupOfKey;
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        if (nodesOfMesh[mesh].empty()) {
            continue;
        }
        const auto& primitives = scene.meshes[mesh].primitives;
        for (std::size_t index = 0; index < primitives.size(); ++index) {
            shaders::ShaderVariantKey shader;
            const std::vector<scene::Semantic> semantics =
                unlitPrimitiveSemantics(gpuScene.animation(), scene::MeshId(mesh), index, shader);
            ENCORE_TRY_ASSIGN(auto bindings,
                              gpuScene.geometry().bind(primitives[index], semantics));
            const PipelineKey key = meshPipelineKey(setup, bindings, shader);
            auto [found, inserted] = groupOfKey.try_emplace(key, mGroups.size());
            if (inserted) {
                ENCORE_TRY_ASSIGN(auto pipeline, mPipelines->get(key));
                mGroups.push_back({pipeline, {}});
            }
            mGroups[found->second].primitives.push_back(
                {std::move(bindings), nodesOfMesh[mesh], shader, index});
        }
    }
    mNodes =
        NodeUniforms(setup.device, setup.queue, *setup.layouts, scene, gpuScene.instanceWorlds());
    mQueue = setup.queue;
    return {};
}

void PipelineCacheStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.setBindGroup(0, mFrameGroup);
    for (const PipelineGroup& group : mGroups) {
        encoder.setPipeline(group.pipeline);
        for (const PrimitiveDraws& primitive : group.primitives) {
            bindGeometry(encoder, primitive.bindings);
            for (std::size_t node : primitive.nodes) {
                encoder.setBindGroup(1, mNodes.bindGroup(node));
                if (primitive.shader.animated()) {
                    mAnimation->bind(encoder, primitive.shader, node, primitive.primitive);
                }
                drawGeometry(encoder, primitive.bindings, 1, 0);
            }
        }
    }
}

void PipelineCacheStrategy::instanceMoved(std::size_t instance, const glm::mat4& world) {
    mNodes.update(mQueue, instance, world);
}

}  // namespace encore::render
