#include "render/strategies/NodeLoopStrategy.h"

namespace encore::render {

Result<void> NodeLoopStrategy::beginPrepare(const RenderSetup& setup, const GpuScene& scene) {
    ENCORE_TRY(NodeUniforms::checkLimit(scene.data(), setup.mappingBudget, strategyName(kind())));
    mFrameGroup = setup.frame->bindGroup();
    mAnimation = scene.animation();
    mMeshes.assign(scene.data().meshes.size(), {});
    return {};
}

void NodeLoopStrategy::finishPrepare(const RenderSetup& setup, const GpuScene& scene) {
    mNodeMeshes.clear();
    for (const scene::Instance& instance : scene.data().instances) {
        mNodeMeshes.push_back(instance.mesh.index());
    }
    mNodes = NodeUniforms(setup.device, setup.queue, *setup.layouts, scene.data(),
                          scene.instanceWorlds());
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

void NodeLoopStrategy::instanceMoved(std::size_t instance, const glm::mat4& world) {
    mNodes.update(mQueue, instance, world);
}

}  // namespace encore::render
