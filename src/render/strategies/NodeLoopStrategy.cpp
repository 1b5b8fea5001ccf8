#include "NodeLoopStrategy.h"

namespace encore::render {

Result<void> NodeLoopStrategy::beginPrepare(const RenderSetup& setup,
                                            const scene::SceneData& scene) {
    ENCORE_TRY(NodeUniforms::checkLimit(scene, setup.mappingBudget, strategyName(kind())));
    mFrameGroup = setup.frame->bindGroup();
    mAnimation = setup.animation;
    mMeshes.assign(scene.meshes.size(), {});
    return {};
}

void NodeLoopStrategy::finishPrepare(const RenderSetup& setup, const scene::SceneData& scene) {
    mNodeMeshes.clear();
    for (const scene::Instance& instance : scene.instances) {
        mNodeMeshes.push_back(instance.mesh.index());
    }
    mNodes = NodeUniforms(setup.device, setup.queue, *setup.layouts, scene);
    mQueue = setup.queue;
}

void NodeLoopStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.setBindGroup(0, mFrameGroup);
    for (std::size_t node = 0; node < mNodeMeshes.size(); ++node) {
        encoder.setBindGroup(1, mNodes.bindGroup(node));
        const auto& primitives = mMeshes[mNodeMeshes[node]];
        for (std::size_t index = 0; index < primitives.size(); ++index) {
            const PreparedPrimitive& primitive = primitives[index];
            encoder.setPipeline(primitive.pipeline);
            if (primitive.shader.animated()) {
                mAnimation->bind(encoder, primitive.shader, node, index);
            }
            bindGeometry(encoder, primitive.bindings);
            drawGeometry(encoder, primitive.bindings, 1, 0);
        }
    }
}

Result<void> NodeLoopStrategy::updateInstance(std::size_t instance, const glm::mat4& world) {
    ENCORE_TRY(checkInstanceIndex(instance, mNodes.size()));
    mNodes.update(mQueue, instance, world);
    return {};
}

}  // namespace encore::render
