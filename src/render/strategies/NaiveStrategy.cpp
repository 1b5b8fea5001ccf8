#include "NaiveStrategy.h"

#include <map>
#include <string>

#include "encore/gpu/Upload.h"
#include "encore/render/GltfToWebGpu.h"
#include "encore/render/PipelineKey.h"
#include "encore/render/VertexBindings.h"

namespace encore::render {


Result<void> NaiveStrategy::prepare(const RenderSetup& setup, const scene::SceneData& scene) {
    ENCORE_TRY(NodeUniforms::checkLimit(scene, setup.mappingBudget, strategyName(kind())));
    mFrameGroup = setup.frame->bindGroup();
    std::map<scene::AccessorId, wgpu::Buffer> accessorBuffers;
    std::map<scene::AccessorId, std::uint32_t> accessorStrides;
    auto bufferFor = [&](scene::AccessorId id, wgpu::BufferUsage usage) {
        auto found = accessorBuffers.find(id);
        if (found != accessorBuffers.end()) {
            return found->second;
        }
        std::uint32_t stride = 0;
        const auto bytes = usage == wgpu::BufferUsage::Index ? scene.packedAccessorBytes(id)
                                                             : paddedVertexElements(scene, id, stride);
        auto buffer = gpu::createBufferWithData(setup.device, usage, bytes,
                                                "accessor " + std::to_string(id.value));
        accessorStrides[id] = stride;
        return accessorBuffers[id] = buffer;
    };

    mMeshes.assign(scene.meshes.size(), {});
    for (std::size_t meshIndex = 0; meshIndex < scene.meshes.size(); ++meshIndex) {
        const scene::Mesh& mesh = scene.meshes[meshIndex];
        for (std::size_t primitiveIndex = 0; primitiveIndex < mesh.primitives.size();
             ++primitiveIndex) {
            const scene::Primitive& primitive = mesh.primitives[primitiveIndex];
            PreparedPrimitive prepared;
            prepared.topology = primitive.topology;
            PipelineKey key;
            key.topology = primitiveTopology(primitive.topology);
            key.colorFormat = setup.colorFormat;
            key.depthFormat = setup.depthFormat;
            key.sampleCount = setup.sampleCount;
            for (scene::Semantic semantic : {scene::Semantic::Position, scene::Semantic::Normal}) {
                const auto accessorId = primitive.attribute(semantic);
                if (!accessorId) {
                    continue;  // The loader guarantees both; keep going rather than crash.
                }
                const scene::Accessor& accessor = scene.accessors[accessorId->index()];
                const auto format = vertexFormat(accessor);
                if (!format) {
                    return makeError(ErrorCode::Unsupported,
                                     "Mesh " + std::to_string(meshIndex) + " primitive " +
                                         std::to_string(primitiveIndex) +
                                         " has an attribute without a WebGPU vertex format.");
                }
                prepared.vertexBuffers.push_back(bufferFor(*accessorId, wgpu::BufferUsage::Vertex));
                key.addBuffer(accessorStrides[*accessorId]);
                key.addAttribute(*format, 0, *shaderLocation(semantic));
            }
            if (primitive.indices) {
                const scene::Accessor& indices = scene.accessors[primitive.indices->index()];
                prepared.indexBuffer = bufferFor(*primitive.indices, wgpu::BufferUsage::Index);
                prepared.indexFormat = indexFormat(indices);
                prepared.count = indices.count;
                if (isStrip(primitive.topology)) {
                    key.stripIndexFormat = prepared.indexFormat;
                }
            } else {
                prepared.count = primitive.vertexCount;
            }
            auto pipeline = createMeshPipeline(
                setup, key,
                "naive mesh " + std::to_string(meshIndex) + " primitive " +
                    std::to_string(primitiveIndex));
            if (!pipeline) {
                return pipeline.error();
            }
            prepared.pipeline = *pipeline;
            mMeshes[meshIndex].push_back(std::move(prepared));
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

void NaiveStrategy::encode(RenderEncoder& encoder, const FrameState&) const {
    encoder.setBindGroup(0, mFrameGroup);
    for (std::size_t node = 0; node < mNodeMeshes.size(); ++node) {
        encoder.setBindGroup(1, mNodes.bindGroup(node));
        for (const PreparedPrimitive& primitive : mMeshes[mNodeMeshes[node]]) {
            encoder.setPipeline(primitive.pipeline);
            for (std::uint32_t slot = 0; slot < primitive.vertexBuffers.size(); ++slot) {
                encoder.setVertexBuffer(slot, primitive.vertexBuffers[slot]);
            }
            if (primitive.indexBuffer) {
                encoder.setIndexBuffer(primitive.indexBuffer, primitive.indexFormat);
                encoder.drawIndexed(primitive.count, 1, 0, 0, 0, primitive.topology);
            } else {
                encoder.draw(primitive.count, 1, 0, 0, primitive.topology);
            }
        }
    }
}

Result<void> NaiveStrategy::updateInstance(std::size_t instance, const glm::mat4& world) {
    ENCORE_TRY(checkInstanceIndex(instance, mNodes.size()));
    mNodes.update(mQueue, instance, world);
    return {};
}

}  // namespace encore::render
