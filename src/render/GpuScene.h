#pragma once

// The GPU side of one loaded scene, built once and shared by every strategy: the geometry
// (bufferViews in shared buffers that are vertex, index and storage buffers at once), the
// instance transforms, the materials (factors, textures with their mip chains, samplers, bind
// groups) and the skinning and morph buffers. Strategies record from it and own only their
// recording structures, so switching strategy uploads nothing again and keeps every edit.
//
// Edits go through the GPU scene and change data in buffers; replacing an image replaces a bind
// group and bumps generation(): whatever recorded that bind group (a render bundle, a draw
// grouping) records again before its next use. Selecting a material variant
// (KHR_materials_variants) changes only which material each primitive draws (materialOf):
// every material of the file is already uploaded, so it uploads nothing and bumps generation()
// for the strategies to regroup.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>

#include "encore/core/Result.h"
#include "encore/scene/AnimationPlayer.h"
#include "encore/scene/SceneData.h"
#include "render/AnimationBuffers.h"
#include "render/InstanceBuffer.h"
#include "render/MaterialResources.h"
#include "render/RenderSetup.h"
#include "render/StagedUploads.h"
#include "render/VertexBindings.h"

namespace encore::render {

class GpuScene {
  public:
    // Uploads `scene` (which, like `setup`, must outlive the result), the animation buffers at
    // `player`'s current pose (null: the rest pose). `staged`: the scene's images and geometry
    // already in staging buffers (StagedUploads.h), used during this call only.
    // Adds its parts to setup.prepareTimes.
    static Result<std::unique_ptr<GpuScene>> create(const RenderSetup& setup,
                                                    const scene::SceneData& scene,
                                                    const scene::AnimationPlayer* player = nullptr,
                                                    const StagedUploads& staged = {});

    // Gives its buffers and textures back to RenderSetup::resources, when set.
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    const scene::SceneData& data() const { return *mScene; }
    const GeometryBuffers& geometry() const { return mGeometry; }
    const InstanceBuffer& instances() const { return mInstances; }
    const MaterialResources& materials() const { return *mMaterials; }
    // Null when the scene has neither skins nor morph targets.
    const AnimationBuffers* animation() const { return mAnimation.get(); }
    // KHR_materials_transmission: the texture transmissive surfaces sample the scene behind
    // them from (TransmissionPass.h); null when no material of the file has transmission, so
    // that such scenes allocate and copy nothing.
    const wgpu::Texture& transmissionBackground() const { return mTransmissionBackground; }

    // Each scene instance's world matrix as last written (updateInstance), for strategies that
    // keep copies of their own (per-node uniforms).
    std::span<const glm::mat4> instanceWorlds() const { return mWorlds; }
    // Incremented whenever a bind group that recordings may hold is replaced, and whenever the
    // selected material variant changes.
    std::uint64_t generation() const { return mMaterials->generation() + mVariantSwitches; }

    // The material primitive `primitive` of `mesh` draws under the selected variant.
    scene::MaterialId materialOf(scene::MeshId mesh, std::size_t primitive) const {
        return mScene->meshes[mesh.index()].primitives[primitive].materialFor(mVariant);
    }
    // KHR_materials_variants: nullopt draws the default materials.
    std::optional<scene::VariantId> variant() const { return mVariant; }
    // Geometry and texture bytes written to the GPU since creation (replaced images included).
    std::uint64_t uploadedBytes() const {
        return mGeometry.uploadedBytes() + mMaterials->uploadedBytes();
    }

    // Edits. `instance` indexes SceneData::instances; errors name what does not exist.
    Result<void> updateInstance(std::size_t instance, const glm::mat4& world);
    Result<void> updateMaterial(scene::MaterialId material, const scene::Material& value);
    // A new sRGB texture with its mip chain for `material`'s base colour; bumps generation().
    // A material without textures becomes textured (its draws need other pipelines).
    Result<void> replaceBaseColorImage(scene::MaterialId material, const scene::Image& image);
    // Selects a material variant of SceneData::variants (nullopt: the default materials);
    // bumps generation() when the selection changes. Errors name a variant that does not exist.
    Result<void> selectVariant(std::optional<scene::VariantId> variant);
    // Uploads the joints and weights that the player's last evaluate() changed.
    AnimationUploadStats writeAnimation(const scene::AnimationPlayer& player);

  private:
    GpuScene(const RenderSetup& setup,
             const scene::SceneData& scene,
             const scene::AnimationPlayer& player,
             StagedGeometry* stagedGeometry,
             const wgpu::CommandEncoder& uploads);
    Result<void> checkMaterial(scene::MaterialId material) const;

    const RenderSetup* mSetup;
    const scene::SceneData* mScene;
    std::unique_ptr<AnimationBuffers> mAnimation;
    GeometryBuffers mGeometry;
    InstanceBuffer mInstances;
    std::optional<MaterialResources> mMaterials;  // Always set once create() returns.
    wgpu::Texture mTransmissionBackground;
    std::vector<glm::mat4> mWorlds;
    std::optional<scene::VariantId> mVariant;
    std::uint64_t mVariantSwitches = 0;
};

}  // namespace encore::render
