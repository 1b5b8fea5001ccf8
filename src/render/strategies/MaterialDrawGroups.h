#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "render/GpuScene.h"
#include "render/PipelineCache.h"
#include "render/RenderEncoder.h"
#include "render/RenderSetup.h"
#include "render/VertexBindings.h"
#include "render/strategies/BundledFrame.h"

namespace encore::render {

// The draws of the case study's Part 5 (glTF materials), grouped for recording: opaque and
// masked geometry pipeline -> material -> primitive, so each material's bind group is set once
// per pipeline that uses it; blended geometry one draw per instance, back to front; materials
// with KHR_materials_transmission grouped like opaque ones but apart, for the transmission
// pass that follows the copy of everything else (render/TransmissionPass.h). The
// strategies that draw materials (materials, bundles, gpu-culling) record from it; it owns the
// pipelines it picks and the vertex bindings, never scene data.
//
// Shader variants differ only where the vertex inputs or the discard differ, or where a
// material binds no texture at all: which slots have textures, extensions and unlit are uniform
// data and 1-pixel default textures.
class MaterialDrawGroups {
  public:
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

    // Which primitives (of a mesh, by index in it) the groups draw, for strategies that draw only
    // part of the scene this way (visibility: what its compute path does not draw).
    using PrimitiveFilter = std::function<bool(scene::MeshId mesh, std::size_t primitive)>;

    // Chooses every primitive's pipeline and groups the draws of `scene` (which, like `setup`,
    // must outlive this); adds the time to setup.prepareTimes.draws. With `filter`, only the
    // primitives it accepts.
    Result<void> prepare(const RenderSetup& setup,
                         const GpuScene& scene,
                         PrimitiveFilter filter = {});
    // Whether a bind group the groups depend on was replaced since they were made (a material
    // that gained textures needs other pipelines), or another material variant was selected.
    bool stale() const { return mGeneration != mScene->generation(); }
    // Groups the draws again with the materials the GPU scene maps the primitives to now,
    // keeping the vertex bindings made before (a variant may need other inputs: those are
    // added).
    Result<void> regroup();
    // regroup() when stale(), else nothing.
    Result<void> refresh();

    const std::vector<PipelineGroup>& opaque() const { return mOpaque; }
    const std::vector<BlendedDraw>& blended() const { return mBlended; }
    // Primitives whose material has KHR_materials_transmission (any alpha mode).
    const std::vector<PipelineGroup>& transmissive() const { return mTransmissive; }
    PipelineCache& pipelines() const { return *mPipelines; }
    const GpuScene& scene() const { return *mScene; }

    // Group 0 (frame) and group 1 (instance transforms).
    void setSharedBindGroups(RenderEncoder& encoder) const;
    void encodeOpaque(RenderEncoder& encoder) const;
    // The transmissive groups, for the transmission pass (group 0 and 1 set as for opaque).
    void encodeTransmissive(RenderEncoder& encoder) const;
    // Records the transmissive surfaces into `bundle` for the transmission pass of the bundled
    // strategies (again only when the scene's resources were replaced).
    void updateTransmissionBundle(BundledFrame& bundle, const RenderSetup& setup) const;
    // Indices into blended(), back to front as seen from `cameraPosition`.
    std::vector<std::uint32_t> blendOrder(const glm::vec3& cameraPosition) const;
    // Blended draws in that order, skipping state that does not change between them.
    void encodeBlended(RenderEncoder& encoder, std::span<const std::uint32_t> order) const;
    // Binds the material of group 2 (its bind group as the GPU scene holds it now).
    void bindMaterial(RenderEncoder& encoder, scene::MaterialId material) const;

  private:
    void encodeGroups(RenderEncoder& encoder, std::span<const PipelineGroup> groups) const;
    // The bindings of a primitive for these inputs, made on first use.
    Result<const PrimitiveBindings*> bindingsFor(std::size_t mesh,
                                                 std::size_t index,
                                                 std::span<const scene::Semantic> semantics);

    // A primitive's first bindings and the semantics (as bits) they bind.
    struct PrimitiveBinding {
        std::uint32_t semantics = 0;
        const PrimitiveBindings* bindings = nullptr;
    };

    const RenderSetup* mSetup = nullptr;
    const GpuScene* mScene = nullptr;
    std::unique_ptr<PipelineCache> mOwnPipelines;
    PipelineCache* mPipelines = nullptr;  // mOwnPipelines or the renderer's kept cache.
    wgpu::BindGroup mFrameGroup;
    std::vector<std::unique_ptr<PrimitiveBindings>> mBindings;  // Stable addresses.
    // [mesh][primitive] -> its first entry of mBindings (null until grouped).
    std::vector<std::vector<PrimitiveBinding>> mPrimitiveBindings;
    // (mesh, primitive, semantics) -> the entries of mBindings for other inputs.
    std::map<std::tuple<std::size_t, std::size_t, std::uint32_t>, const PrimitiveBindings*>
        mOtherBindings;
    std::vector<PipelineGroup> mOpaque;
    std::vector<BlendedDraw> mBlended;
    std::vector<PipelineGroup> mTransmissive;
    std::uint64_t mGeneration = 0;
    PrimitiveFilter mFilter;
};

}  // namespace encore::render
