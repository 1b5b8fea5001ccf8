#include "render/strategies/LayoutsStrategy.h"

#include <string>

#include "render/AnimationBuffers.h"
#include "render/PipelineKey.h"

namespace encore::render {

Result<void> LayoutsStrategy::prepare(const RenderSetup& setup, const GpuScene& gpuScene) {
    ENCORE_TRY(beginPrepare(setup, gpuScene));
    const scene::SceneData& scene = gpuScene.data();
    for (std::size_t mesh = 0; mesh < scene.meshes.size(); ++mesh) {
        for (std::size_t index = 0; index < scene.meshes[mesh].primitives.size(); ++index) {
            shaders::ShaderVariantKey shader;
            const std::vector<scene::Semantic> semantics =
                unlitPrimitiveSemantics(gpuScene.animation(), scene::MeshId(mesh), index, shader);
            ENCORE_TRY_ASSIGN(auto bindings, gpuScene.geometry().bind(
                                                 scene.meshes[mesh].primitives[index], semantics));
            const PipelineKey key = meshPipelineKey(setup, bindings, shader);
            ENCORE_TRY_ASSIGN(auto pipeline,
                              createMeshPipeline(setup, key,
                                                 "layouts mesh " + std::to_string(mesh) +
                                                     " primitive " + std::to_string(index)));
            mMeshes[mesh].push_back({pipeline, std::move(bindings), shader});
        }
    }
    finishPrepare(setup, gpuScene);
    return {};
}

}  // namespace encore::render
