#pragma once

#include <memory>
#include <span>
#include <vector>

#include "encore/render/AnimationBuffers.h"
#include "encore/render/InstanceBuffer.h"
#include "encore/render/MaterialResources.h"
#include "encore/render/PipelineCache.h"
#include "encore/render/Strategy.h"
#include "encore/render/VertexBindings.h"

namespace encore::render {

// The case study's Part 5: glTF materials (base colour factor and texture with its sampler,
// vertex colours, alpha MASK and BLEND, double-sided culling), shader variants only where the
// vertex inputs or the discard differ, one bind group per material. Opaque and masked geometry
// is drawn pipeline -> material -> primitive, so each material's bind group is set once per
// pipeline that uses it; blended geometry follows, one draw per instance, back to front.
class MaterialsStrategy : public Strategy {
  public:
    StrategyKind kind() const override { return StrategyKind::Materials; }
    Result<void> prepare(const RenderSetup& setup, const scene::SceneData& scene) override;
    void encode(RenderEncoder& encoder, const FrameState& frame) const override;
    InstanceTransformTargets instanceTransformTargets() const override {
        return mInstances.transformTargets();
    }
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world) override;
    Result<void> updateMaterial(scene::MaterialId material, const scene::Material& value) override;
    Result<void> replaceBaseColorImage(scene::MaterialId material,
                                       const scene::Image& image) override;

    const InstanceBuffer& instances() const { return mInstances; }
    MaterialResources& materials() { return *mMaterials; }
    std::size_t pipelineCount() const { return mPipelines ? mPipelines->size() : 0; }

  protected:
    struct PrimitiveDraw {
        const PrimitiveBindings* bindings = nullptr;
        InstanceRange instances;
        // The animation draw record (animated variants): the range's first scene instance and
        // the primitive's index in its mesh.
        std::size_t sceneInstance = 0;
        std::size_t primitive = 0;
    };
    struct MaterialGroup {
        scene::MaterialId material;
        std::vector<PrimitiveDraw> primitives;
    };
    struct PipelineGroup {
        PipelineKey key;
        wgpu::RenderPipeline pipeline;
        std::vector<MaterialGroup> materials;
    };
    // One blended primitive of one instance, sorted by distance every frame.
    struct BlendedDraw {
        wgpu::RenderPipeline pipeline;
        scene::MaterialId material;
        const PrimitiveBindings* bindings = nullptr;
        std::uint32_t instanceSlot = 0;
        glm::vec3 center{0.0f};  // World-space centre of the primitive's bounds.
        shaders::ShaderVariantKey shader;
        std::size_t primitive = 0;  // Index in its mesh.
    };

    // Opaque and masked groups (shared with the bundle strategies, which record them once).
    void encodeOpaque(RenderEncoder& encoder) const;
    // Indices into mBlended, back to front as seen from `cameraPosition`.
    std::vector<std::uint32_t> blendOrder(const glm::vec3& cameraPosition) const;
    // Blended draws in that order, skipping state that does not change between them.
    void encodeBlended(RenderEncoder& encoder, std::span<const std::uint32_t> order) const;
    void setSharedBindGroups(RenderEncoder& encoder) const;
    // Chooses every primitive's pipeline and groups the draws (mOpaque, mBlended) from the
    // prepared scene and materials; again when a material gains textures. Strategies that
    // derive their own structures from the groups extend it.
    virtual Result<void> groupDraws();

    const RenderSetup* mSetup = nullptr;
    const scene::SceneData* mScene = nullptr;
    std::unique_ptr<GeometryBuffers> mGeometry;
    std::unique_ptr<PipelineCache> mOwnPipelines;
    PipelineCache* mPipelines = nullptr;  // mOwnPipelines or the renderer's kept cache.
    std::unique_ptr<MaterialResources> mMaterials;
    wgpu::BindGroup mFrameGroup;
    InstanceBuffer mInstances;
    wgpu::Queue mQueue;
    std::vector<std::unique_ptr<PrimitiveBindings>> mBindings;  // Stable addresses.
    // [mesh][primitive] -> its entry of mBindings (null until grouped).
    std::vector<std::vector<const PrimitiveBindings*>> mPrimitiveBindings;
    std::vector<PipelineGroup> mOpaque;
    std::vector<BlendedDraw> mBlended;
    const AnimationBuffers* mAnimation = nullptr;
};

}  // namespace encore::render
