#include "LayoutsStrategy.h"

#include <string>

#include "encore/render/PipelineKey.h"
#include "encore/render/ShadingSemantics.h"

namespace encore::render {

Result<void> LayoutsStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    ENCORE_TRY(NodeUniforms::checkLimit(scene, setup.mappingBudget, strategyName(kind())));
    mFrameGroup = setup.frame->bindGroup();
    mGeometry = std::make_unique<GeometryBuffers>(setup.device, scene);
    mMeshes.assign(scene.meshes.size(), {});
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        for (std::size_t index = 0; index < scene.meshes[mesh].primitives.size(); ++index) {
            auto bindings = mGeometry->bind(scene.meshes[mesh].primitives[index],
                                            kUnlitTransformSemantics);
            if (!bindings) {
                return bindings.error();
            }
            const PipelineKey key = meshPipelineKey(setup, *bindings, {});
            auto pipeline = createMeshPipeline(setup, key,
                                               "layouts mesh " + std::to_string(mesh) +
                                                   " primitive " + std::to_string(index));
            if (!pipeline) {
                return pipeline.error();
            }
            mMeshes[mesh].push_back({*pipeline, std::move(*bindings)});
        }
    }
    mNodeMeshes.clear();
    for (const scene::Instance& instance : scene.instances) {
        mNodeMeshes.push_back(instance.mesh.index());
    }
    mNodes = NodeUniforms(setup.device, setup.queue, *setup.layouts, scene);
    mQueue = setup.queue;
    return {};
}

void LayoutsStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.setBindGroup(0, mFrameGroup);
    for (std::size_t node = 0; node < mNodeMeshes.size(); ++node) {
        encoder.setBindGroup(1, mNodes.bindGroup(node));
        for (const PreparedPrimitive& primitive : mMeshes[mNodeMeshes[node]]) {
            encoder.setPipeline(primitive.pipeline);
            bindGeometry(encoder, primitive.bindings);
            drawGeometry(encoder, primitive.bindings, 1, 0);
        }
    }
}

Result<void> LayoutsStrategy::updateInstance(std::size_t instance, const glm::mat4& world) {
    ENCORE_TRY(checkInstanceIndex(instance, mNodes.size()));
    mNodes.update(mQueue, instance, world);
    return {};
}

}  // namespace encore::render
