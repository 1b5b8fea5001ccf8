#include "render/strategies/NaiveStrategy.h"

#include <map>
#include <string>

#include "gpu/Upload.h"
#include "render/AnimationBuffers.h"
#include "render/GltfToWebGpu.h"
#include "render/PipelineKey.h"
#include "render/VertexBindings.h"

namespace encore::render {

Result<void> NaiveStrategy::prepare(const RenderSetup& setup, const GpuScene& gpuScene) {
    ENCORE_TRY(beginPrepare(setup, gpuScene));
    // Naive's very point: every accessor in a buffer of its own, not the GPU scene's geometry.
    const scene::SceneData& scene = gpuScene.data();
    std::map<scene::AccessorId, wgpu::Buffer> accessorBuffers;
    std::map<scene::AccessorId, std::uint32_t> accessorStrides;
    auto bufferFor = [&](scene::AccessorId id, wgpu::BufferUsage usage) {
        auto found = accessorBuffers.find(id);
        if (found != accessorBuffers.end()) {
            return found->second;
        }
        std::uint32_t stride = 0;
        const auto bytes = usage == wgpu::BufferUsage::Index
                               ? scene.packedAccessorBytes(id)
                               : paddedVertexElements(scene, id, stride);
        auto buffer = gpu::createBufferWithData(setup.device, usage, bytes,
                                                "accessor " + std::to_string(id.value));
        accessorStrides[id] = stride;
        return accessorBuffers[id] = buffer;
    };

    for (std::size_t meshIndex = 0; meshIndex < scene.meshes.size(); ++meshIndex) {
        const scene::Mesh& mesh = scene.meshes[meshIndex];
        for (std::size_t primitiveIndex = 0; primitiveIndex < mesh.primitives.size();
             ++primitiveIndex) {
            const scene::Primitive& primitive = mesh.primitives[primitiveIndex];
            PreparedPrimitive prepared;
            PrimitiveBindings& bindings = prepared.bindings;
            bindings.topology = primitive.topology;
            bindings.vertexCount = primitive.vertexCount;
            PipelineKey key;
            key.topology = primitiveTopology(primitive.topology);
            key.colorFormat = setup.colorFormat;
            key.depthFormat = setup.depthFormat;
            key.sampleCount = setup.sampleCount;
            const std::vector<scene::Semantic> semantics = unlitPrimitiveSemantics(
                gpuScene.animation(), scene::MeshId(meshIndex), primitiveIndex, key.shader);
            prepared.shader = key.shader;
            for (scene::Semantic semantic : semantics) {
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
                bindings.vertexBuffers.push_back(
                    {bufferFor(*accessorId, wgpu::BufferUsage::Vertex), 0});
                key.addBuffer(accessorStrides[*accessorId]);
                key.addAttribute(*format, 0, *shaderLocation(semantic));
            }
            if (primitive.indices) {
                const scene::Accessor& indices = scene.accessors[primitive.indices->index()];
                bindings.indices =
                    IndexBufferBinding{bufferFor(*primitive.indices, wgpu::BufferUsage::Index),
                                       indexFormat(indices), 0, indices.count};
                if (isStrip(primitive.topology)) {
                    key.stripIndexFormat = bindings.indices->format;
                }
            }
            ENCORE_TRY_ASSIGN(
                prepared.pipeline,
                createMeshPipeline(setup, key,
                                   "naive mesh " + std::to_string(meshIndex) + " primitive " +
                                       std::to_string(primitiveIndex)));
            mMeshes[meshIndex].push_back(std::move(prepared));
        }
    }

    finishPrepare(setup, gpuScene);
    return {};
}

}  // namespace encore::render
